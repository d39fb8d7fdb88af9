"""Regenerate only the "Dynamics speed" section of docs/benchmarks.md (`mechkit.bench.dynamics_speed`), every
mechanism measured in one run, with the machine's load beside the figures and each target met or missed.

Usage: OPENBLAS_NUM_THREADS=1 python tools/dynamics_speed.py [--budget SECONDS] [NAME ...]
(the whole page: tools/bench_all.py --speed). Run it on an idle machine: the ratios are of interleaved minima,
the microseconds those of the machine as it was.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from mechkit.bench import dynamics_speed
from mechkit.bench.markdown import replace_section
from mechkit.catalog import registry
from mechkit.loading import load

HEADING = "## Dynamics speed"
PAGE = Path(__file__).resolve().parent.parent / "docs" / "benchmarks.md"


def summary(results: list[dynamics_speed.MechanismSpeed]) -> list[str]:
    """One line per target: on how many mechanisms it is met, and the value of each it misses."""
    lines = []
    for label in dict.fromkeys(t.label for r in results for t in r.targets):
        found = [(r.name, t) for r in results for t in r.targets if t.label == label]
        missed = [f"{n} {t.value:.2f} (<= {t.limit:g})" for n, t in found if not t.met]
        met = len(found) - len(missed)
        lines.append(f"- {label}: met on {met}/{len(found)}" + (f"; missed on {', '.join(missed)}" if missed else ""))
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="mechanisms (default: every registered one)")
    parser.add_argument("--budget", type=float, default=0.3, help="seconds of timing per row")
    args = parser.parse_args(argv)
    names = args.names or list(registry.names())
    before = os.getloadavg()[0]
    results = [dynamics_speed.measure(load(n), args.budget) for n in names]
    after = os.getloadavg()[0]
    threads = os.environ.get("OPENBLAS_NUM_THREADS", "OpenBLAS's default")
    intro = dynamics_speed.__doc__.split("\n\n")[1].replace("\n", " ")
    machine = (
        f"Measured in one run on this {os.cpu_count()}-core machine, OPENBLAS_NUM_THREADS={threads}, load average "
        f"{before:.1f} before and {after:.1f} after the run (`python tools/dynamics_speed.py`)."
    )
    text = [HEADING, "", intro, "", machine, "", "Targets in this run:", "", *summary(results), ""]
    text += dynamics_speed.markdown(results)
    replace_section(PAGE, HEADING, "\n".join(text) + "\n")
    print(f"wrote {PAGE} ({HEADING[3:]}; load {before:.1f} -> {after:.1f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
