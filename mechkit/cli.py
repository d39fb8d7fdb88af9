"""The `mechkit` command line: list, urdf, report, snapshot."""

from __future__ import annotations

import argparse
import json
import os
import sys

import numpy as np

from mechkit.exceptions import MechkitError


def _overrides(pairs: list[str]) -> dict[str, str]:
    out = {}
    for pair in pairs or []:
        if "=" not in pair:
            raise MechkitError(f"--set expects name=value, got {pair!r}")
        key, value = pair.split("=", 1)
        out[key.strip()] = value.strip()
    return out


def _load(args):
    from mechkit.mechanism import load

    return load(args.name, **_overrides(args.set))


def cmd_list(args) -> None:
    from mechkit.registry import ENTRIES

    for e in ENTRIES:
        print(f"{e.name:<22} {e.summary}")


def cmd_urdf(args) -> None:
    from mechkit.description import render_urdf
    from mechkit.mechanism import from_params
    from mechkit.registry import get_spec

    spec = get_spec(args.name)
    params = spec.params.from_overrides(**_overrides(args.set))
    from_params(spec, params)  # validates: the URDF builds and assembles
    text = render_urdf(spec.template_path, params.xacro_args())
    if args.output:
        from mechkit.atomic import write_text

        write_text(args.output, text)
    else:
        sys.stdout.write(text)


def cmd_report(args) -> None:
    from mechkit.report import format_report, report

    r = report(_load(args))
    print(json.dumps(r, indent=2) if args.json else format_report(r))


def cmd_snapshot(args) -> None:
    from mechkit.viz import snapshot_command

    for path in snapshot_command(_load(args), q=args.q, scene=args.scene, html=args.output, png=args.png):
        print(f"wrote {path}")


class ProgressBar:
    """A one-line progress bar per mechanism on stderr (a `mechkit.bench.run.Progress` callback), shown
    only on a terminal or when MECHKIT_PROGRESS=1."""

    def __init__(self, enabled: bool | None = None):
        self.enabled = (sys.stderr.isatty() or os.environ.get("MECHKIT_PROGRESS") == "1") if enabled is None else enabled

    def __call__(self, label: str, done: int, total: int, what: str = "") -> None:
        if self.enabled:
            width, total = 30, max(total, 1)
            filled = int(width * done / total)
            sys.stderr.write(f"\r{label} [{'#' * filled}{'.' * (width - filled)}] {done}/{total} {what[:40]:<40}")
            if done >= total:
                sys.stderr.write("\n")
            sys.stderr.flush()


def cmd_bench(args) -> None:
    from pathlib import Path

    from mechkit.atomic import write_text
    from mechkit.bench import charts, failure_atlas, loadtime, markdown, run, scale

    with np.errstate(under="ignore"):
        results, skipped = run.run(args.names, args.quick, progress=ProgressBar())
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


def cmd_export(args) -> None:
    from mechkit.export import export_command

    for path in export_command(_load(args), args.format, args.output):
        print(f"wrote {path}")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="mechkit", description="Closed-loop mechanisms on Pinocchio.")
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("list", help="registered mechanisms").set_defaults(func=cmd_list)

    def with_name(name: str, help: str):
        p = sub.add_parser(name, help=help)
        p.add_argument("name", help="mechanism name (see `mechkit list`)")
        p.add_argument("--set", action="append", metavar="NAME=VALUE", help="override a parameter (SI units, rad)")
        return p

    p = with_name("urdf", "print or write the URDF generated from the parameters")
    p.add_argument("-o", "--output", help="file to write (default: stdout)")
    p.set_defaults(func=cmd_urdf)
    p = with_name("report", "structure, mobility and self-checks")
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(func=cmd_report)
    p = with_name("snapshot", "self-contained meshcat HTML (and PNG) of a pose or an animated scene")
    p.add_argument("--q", help="input coordinates, comma-separated, in actuated order (rad or m)")
    p.add_argument("--scene", help="animate a scene of the mechanism (see its module), instead of one pose")
    p.add_argument("-o", "--output", help="HTML file to write")
    p.add_argument("--png", help="PNG screenshot to write (needs a headless Chromium)")
    p.set_defaults(func=cmd_snapshot)
    p = sub.add_parser("bench", help="speed and accuracy of every method, per mechanism")
    p.add_argument("names", nargs="*", help="mechanisms (default: all)")
    p.add_argument("--quick", action="store_true", help="few repetitions, smallest sweeps")
    p.add_argument("--charts", help="folder for the error-vs-time charts (PNG and SVG)")
    p.add_argument("--markdown", help="write the summary table (docs/benchmarks.md)")
    p.set_defaults(func=cmd_bench)
    p = with_name("export", "write the mechanism for other tools")
    p.add_argument("--format", required=True, choices=["mjcf", "extended-urdf"], help="target format")
    p.add_argument("-o", "--output", required=True, help="file to write (extended-urdf also writes a .yaml beside it)")
    p.set_defaults(func=cmd_export)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        with np.errstate(all="raise"):
            args.func(args)
    except MechkitError as err:
        print(f"mechkit: error: {err}", file=sys.stderr)
        return 2
    except FloatingPointError as err:
        print(f"mechkit: error: numerical failure ({err})", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
