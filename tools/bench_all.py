"""Regenerate docs/benchmarks.md and docs/figures/bench_*.{png,svg}: `mechkit bench` over every mechanism.

Usage: python tools/bench_all.py [--quick] [--speed] [NAME ...]
(Drake rows appear when `pydrake` is importable: `pip install drake`.) With --speed the page also gets
the load times of the field's robots (`mechkit.bench.field`, section "Loading the field's robots").
"""

from __future__ import annotations

import sys
from pathlib import Path

from mechkit.cli import main

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"

if __name__ == "__main__":
    code = main(["bench", *sys.argv[1:], "--charts", str(DOCS / "figures"), "--markdown", str(DOCS / "benchmarks.md")])
    if code == 0 and "--speed" in sys.argv[1:]:
        from mechkit.bench import field

        field.add_section(DOCS / "benchmarks.md", ROOT / "tests" / "fixtures" / "field", quick="--quick" in sys.argv[1:])
    sys.exit(code)
