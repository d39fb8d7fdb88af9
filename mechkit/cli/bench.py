"""`mechkit bench`: speed and accuracy of every method per mechanism, peers beside ours."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from mechkit.atomic import write_text
from mechkit.cli.common import examples


def run(args: argparse.Namespace) -> None:
    """Measure, print the tables and goals, and write the charts and the page when asked."""
    from mechkit.bench import charts, failure_atlas, loadtime, markdown, run, scale
    from mechkit.cli.progress import ProgressBars

    with np.errstate(under="ignore"):
        results, skipped = run.run(args.names, args.quick, progress=ProgressBars())
        for b in results:
            print(markdown.format_table(b))
        for line in markdown.goals(results):
            print(line)
        for name, why in skipped.items():
            print(f"{name}: not measured ({why})")
        fits = scale.scale_fits(results)
        for name, pts, slope in fits:
            print(f"scale: {name}: t ~ nv^{slope:.2f} (" + ", ".join(f"{m} nv={n}: {t * 1e6:.1f} us" for m, n, t in pts) + ")")
        first = loadtime.first_load(runs=5 if args.quick else 15)
        print("\n".join(["first load in a fresh process:", *markdown.first_load_lines(first)]))
        figures = []
        if args.charts:
            figures = charts.draw_all(results, fits, Path(args.charts))
            print(f"wrote {len(figures)} charts to {args.charts}")
        if args.markdown:
            failures = []
            if args.charts:
                failures = failure_atlas.summary_lines(Path(args.charts), quick=args.quick)
                figures += sorted(Path(args.charts).glob("bench_atlas_*.png"))
            write_text(args.markdown, markdown.markdown_report(results, args.quick, figures, failures, skipped, fits, first))
            print(f"wrote {args.markdown}")


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `bench`."""
    p = sub.add_parser("bench", help="speed and accuracy of every method, per mechanism", **examples(
        "mechkit bench four_bar --quick", "mechkit bench --charts docs/bench --markdown docs/benchmarks.md"))
    p.add_argument("names", nargs="*", help="mechanisms (default: all)")
    p.add_argument("--quick", action="store_true", help="few repetitions, smallest sweeps")
    p.add_argument("--charts", help="folder for the error-vs-time charts (PNG and SVG)")
    p.add_argument("--markdown", help="write the summary table (docs/benchmarks.md)")
    p.set_defaults(func=run)
