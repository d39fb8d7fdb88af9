"""Regenerate the measured sections of docs/iftomm_benchmarks.md (`mechkit.bench.iftomm_page.write_page`, and
`mechkit.bench.iftomm_spring.write_section`: the four-bar with a diagonal spring).

Usage: python tools/iftomm_benchmarks.py [--fast]   (--fast: without the N = 40 four-bar)
"""

from __future__ import annotations

import sys
from pathlib import Path

from mechkit.bench import iftomm_page, iftomm_spring

if __name__ == "__main__":
    docs = Path(__file__).resolve().parent.parent / "docs"
    iftomm_page.write_page(docs, slow="--fast" not in sys.argv[1:])
    iftomm_spring.write_section(docs)
