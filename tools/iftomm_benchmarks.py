"""Regenerate the "Measured" section of docs/iftomm_benchmarks.md (`mechkit.bench.iftomm_page.write_page`).

Usage: python tools/iftomm_benchmarks.py [--fast]   (--fast: without the N = 40 four-bar)
"""

from __future__ import annotations

import sys
from pathlib import Path

from mechkit.bench import iftomm_page

if __name__ == "__main__":
    iftomm_page.write_page(Path(__file__).resolve().parent.parent / "docs", slow="--fast" not in sys.argv[1:])
