"""Regenerate docs/benchmarks.md and docs/figures/bench_*.{png,svg}: `mechkit bench` over every mechanism,
then the simulator against MuJoCo on the small mechanisms (`mechkit.bench.simulation_speed`) and their
work-precision charts (`mechkit.bench.work_precision`).

Usage: python tools/bench_all.py [--quick] [--speed] [NAME ...]
(Drake rows appear when `pydrake` is importable: `pip install drake`.) With --speed, the page also gets
the speed rows (`mechkit bench --speed`), the elastic ones among them (`mechkit.bench.elastic_speed`),
and the load times of the field's robots (`mechkit.bench.field`, section "Loading the field's robots");
run it as OPENBLAS_NUM_THREADS=1 python tools/bench_all.py --speed for figures a busy machine does
not distort.
"""

from __future__ import annotations

import sys
from pathlib import Path

import mechkit
from mechkit.bench import simulation_speed, work_precision
from mechkit.cli import main

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"

if __name__ == "__main__":
    code = main(["bench", *sys.argv[1:], "--charts", str(DOCS / "figures"), "--markdown", str(DOCS / "benchmarks.md")])
    rows = [
        simulation_speed.simulation_speed(mechkit.load(name), 0.1, method)
        for name in simulation_speed.SMALL
        for method in ("RK45", "RK4", "SymplecticEuler")
    ]
    simulation_speed.write_section(DOCS / "benchmarks.md", rows)
    work_precision.write_section(DOCS, work_precision.PROBLEMS)
    if code == 0 and "--speed" in sys.argv[1:]:
        from mechkit.bench import field

        field.add_section(
            DOCS / "benchmarks.md", ROOT / "tests" / "fixtures" / "field", quick="--quick" in sys.argv[1:]
        )
    sys.exit(code)
