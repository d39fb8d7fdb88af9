"""`mechkit bench`: speed and accuracy of every method per mechanism, peers beside ours."""

from __future__ import annotations

import argparse
from pathlib import Path

from mechkit.base.atomic import resolve_output, write_text
from mechkit.base.exceptions import OutputError
from mechkit.cli.common import examples
from mechkit.loading import resolve


def run(args: argparse.Namespace) -> None:
    """Measure, print the tables and goals, and write the charts and the page when asked.

    Args:
        args: the parsed command line.

    Raises:
        OutputError: --charts names something other than a folder, or --markdown cannot be written.
        InvalidParameters: an unknown mechanism.
    """
    from mechkit.bench import charts, failure_atlas, loadtime, markdown, run, scale
    from mechkit.cli.progress import ProgressBars

    for name in args.names:
        resolve(name)  # an unknown name fails now, not as "not measured" after the run
    if args.markdown:
        resolve_output(args.markdown)  # refused before the run, not after it
    if args.charts and Path(args.charts).exists() and not Path(args.charts).is_dir():
        raise OutputError(args.charts, "--charts needs a folder")
    results, skipped = run.run(args.names, args.quick, progress=ProgressBars())
    for b in results:
        print(markdown.format_table(b))
    for line in markdown.goals(results):
        print(line)
    for name, why in skipped.items():
        print(f"{name}: not measured ({why})")
    fits = scale.scale_fits(results)
    for name, pts, slope in fits:
        print(
            f"scale: {name}: t ~ nv^{slope:.2f} (" + ", ".join(f"{m} nv={n}: {t * 1e6:.1f} us" for m, n, t in pts) + ")"
        )
    sections = speed_sections(args.names, args.quick) if args.speed else {}
    for title, body in sections.items():
        print("\n".join([f"{title}:", *body]))
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
        write_text(
            args.markdown,
            markdown.markdown_report(results, args.quick, figures, failures, skipped, fits, first, sections),
        )
        print(f"wrote {args.markdown}")


def speed_sections(names: list[str], quick: bool) -> dict[str, list[str]]:
    """The speed sections of the benchmark page: the dynamics against one raw Pinocchio call, the ladder
    of four-bar loops, the 2T1R motion law, loading from files, the second opinion, and the elastic
    quantities.

    Args:
        names: the mechanisms (default: every registered one).
        quick: short timing budgets.

    Returns:
        Section title -> its markdown lines.
    """
    from mechkit.bench import (
        dynamics_speed,
        elastic_speed,
        ladder,
        load_speed,
        motion_speed,
        second_opinion_speed,
    )
    from mechkit.catalog import registry
    from mechkit.loading import load

    budget = 0.05 if quick else 0.3
    chosen = names or list(registry.names())
    speed = [dynamics_speed.measure(load(n), budget) for n in chosen]
    points = ladder.run(ladder.SIZES, budget)

    def intro(module) -> str:
        return module.__doc__.split("\n\n")[0].replace("\n", " ")

    return {
        "Dynamics speed": [
            dynamics_speed.__doc__.split("\n\n")[1].replace("\n", " "),
            "",
            *dynamics_speed.markdown(speed),
        ],
        "Ladder of four-bar loops": [ladder.__doc__.split("\n\n")[1].replace("\n", " "), "", *ladder.markdown(points)],
        "Motion law": [
            intro(motion_speed),
            "",
            *motion_speed.lines(motion_speed.motion_law_speed(repeats=2 if quick else 5)),
        ],
        "Loading from a file": [
            intro(load_speed),
            "",
            *load_speed.lines(load_speed.load_times(repeats=3 if quick else 15)),
        ],
        "Second opinion": [
            intro(second_opinion_speed),
            "",
            *second_opinion_speed.lines(
                second_opinion_speed.second_opinion_rows(chosen, samples=3 if quick else 6, budget_s=budget)
            ),
        ],
        "Elastic": [intro(elastic_speed), "", *elastic_speed.lines(elastic_speed.rows(budget, 3 if quick else 5))],
    }


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `bench`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "bench",
        help="speed and accuracy of every method, per mechanism",
        **examples("mechkit bench four_bar --quick", "mechkit bench --charts docs/bench --markdown docs/benchmarks.md"),
    )
    p.add_argument("names", nargs="*", help="mechanisms (default: all)")
    p.add_argument("--quick", action="store_true", help="few repetitions, smallest sweeps")
    p.add_argument("--charts", help="folder for the error-vs-time charts (PNG and SVG)")
    p.add_argument("--markdown", help="write the summary table (docs/benchmarks.md)")
    p.add_argument(
        "--speed",
        action="store_true",
        help=(
            "also the dynamics speed rows, the ladder of four-bar loops, the 2T1R motion law, loading from files "
            "and the second opinion"
        ),
    )
    p.set_defaults(func=run)
