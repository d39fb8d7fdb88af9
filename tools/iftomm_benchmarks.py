"""Regenerate the measured sections of docs/iftomm_benchmarks.md (`mechkit.bench.iftomm_page.write_page`, and
`mechkit.bench.iftomm_spring.write_section`: the four-bar with a diagonal spring).

Usage: python tools/iftomm_benchmarks.py [--fast] [--only KEY ...]
  --fast: without the N = 40 four-bar; --only: measure these problems (`iftomm_page.PROBLEMS`: pendulum,
  n_four_bar_2, bricard, flyball, n_four_bar_40; spring_four_bar, spatial_slider_crank: their sections) again and keep
  the page's rows of the others.
"""

from __future__ import annotations

import sys
from pathlib import Path

from mechkit.bench import iftomm_page, iftomm_slider_crank, iftomm_spring

if __name__ == "__main__":
    args = sys.argv[1:]
    only = args[args.index("--only") + 1 :] if "--only" in args else None
    docs = Path(__file__).resolve().parent.parent / "docs"
    sections = {
        "spring_four_bar": iftomm_spring.write_section,
        "spatial_slider_crank": iftomm_slider_crank.write_section,
    }
    page = None if only is None else [k for k in only if k not in sections]
    if page is None or page:
        iftomm_page.write_page(docs, slow="--fast" not in args, only=page)
    for key, write in sections.items():
        if only is None or key in only:
            write(docs)
