"""Regenerate docs/reactions_vs_engines.md: mechkit's rigid reactions beside Drake's and MuJoCo's.

Usage: python tools/reactions_vs_engines.py (needs `pip install 'mechkit[peers]'`: Drake and MuJoCo).
"""

from __future__ import annotations

from pathlib import Path

import mechkit
from mechkit.bench import reactions_page

ROOT = Path(__file__).resolve().parent.parent

if __name__ == "__main__":
    mechanisms = {name: mechkit.load(name) for name in ("four_bar", "parallel_2t1r")}
    mechanisms["robotiq_2f85 (menagerie)"] = mechkit.load(ROOT / "tests/fixtures/field/menagerie/robotiq_2f85/2f85.xml")
    reactions_page.write(ROOT / "docs" / "reactions_vs_engines.md", mechanisms)
