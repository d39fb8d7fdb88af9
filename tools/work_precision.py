"""Regenerate the "Work-precision" section of docs/benchmarks.md and its charts
docs/figures/work_precision_<mechanism>.png (`mechkit.bench.work_precision`).

Usage: python tools/work_precision.py [NAME ...]   (default: four_bar five_bar ten_bar; about a minute)
"""

from __future__ import annotations

import sys
from pathlib import Path

import mechkit
from mechkit.base.plotting import save_figure
from mechkit.bench import work_precision as wp
from mechkit.bench.markdown import replace_section

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"


def main(names: list[str]) -> int:
    problems, charts = {}, {}
    for name in names:
        mech = mechkit.load(name)
        q_end = wp.reference(mech)
        problems[name] = wp.mechkit_points(mech, q_end) + wp.mujoco_points(mech, q_end)
        chart = f"figures/work_precision_{name}.png"
        save_figure(wp.figure(name, problems[name]), DOCS / chart)
        charts[name] = chart
        print(f"{name}: {len(problems[name])} runs")
    replace_section(DOCS / "benchmarks.md", wp.HEADING, wp.markdown(problems, charts))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:] or ["four_bar", "five_bar", "ten_bar"]))
