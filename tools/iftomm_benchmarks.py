"""Regenerate the "Measured" section of docs/iftomm_benchmarks.md (`mechkit.bench.iftomm_page.write_page`).

Usage: python tools/iftomm_benchmarks.py [--fast] [--only KEY ...]
  --fast: without the N = 40 four-bar; --only: measure these problems (`iftomm_page.PROBLEMS`: pendulum,
  n_four_bar_2, bricard, flyball, n_four_bar_40) again and keep the page's rows of the others.
"""

from __future__ import annotations

import sys
from pathlib import Path

from mechkit.bench import iftomm_page

if __name__ == "__main__":
    args = sys.argv[1:]
    only = args[args.index("--only") + 1 :] if "--only" in args else None
    iftomm_page.write_page(Path(__file__).resolve().parent.parent / "docs", slow="--fast" not in args, only=only)
