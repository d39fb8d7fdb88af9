"""Regenerate the "Work-precision" section of docs/benchmarks.md and its charts
docs/figures/work_precision_<mechanism>.png (`mechkit.bench.work_precision.write_section`): the mechanisms
named (their MJCF export) and the field robot, the Robotiq 2F-85 (its Menagerie file read by both codes).

Usage: python tools/work_precision.py [NAME ...]   (default: `mechkit.bench.work_precision.PROBLEMS`; under a minute)
"""

from __future__ import annotations

import sys
from pathlib import Path

from mechkit.bench import work_precision

if __name__ == "__main__":
    work_precision.write_section(
        Path(__file__).resolve().parent.parent / "docs", sys.argv[1:] or work_precision.PROBLEMS
    )
