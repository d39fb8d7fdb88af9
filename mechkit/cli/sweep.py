"""`mechkit sweep`: evaluate many designs of a mechanism on Dask, one Parquet row per design."""

from __future__ import annotations

import argparse
import sys

from mechkit.base.exceptions import InvalidParameters
from mechkit.cli.common import examples, overrides


def _space(args: argparse.Namespace):
    from mechkit.sweep.space import DesignSpace, parse_axis

    if args.random and args.lhs:
        raise InvalidParameters("random/lhs", (args.random, args.lhs), "choose one sampling: --random N or --lhs N")
    mode, count = ("random", args.random) if args.random else ("lhs", args.lhs) if args.lhs else ("grid", 0)
    return DesignSpace(tuple(parse_axis(a) for a in args.grid or []), mode, count, args.seed)


def _show(design: dict[str, float]) -> str:
    return ", ".join(f"{k}={v:.6g}" for k, v in design.items())


def run(args: argparse.Namespace) -> None:
    """Run (or resume) the sweep, with a progress bar on stderr and a summary on stdout."""
    from tqdm import tqdm

    from mechkit.sweep import engine, store
    from mechkit.sweep.metrics import Study
    from mechkit.sweep.space import DesignSpace

    if args.resume and not args.grid:  # resume what the folder holds
        manifest = store.read_manifest(args.output)
        space, study = DesignSpace.from_dict(manifest["space"]), Study(**manifest["study"])
        metrics, base, size = tuple(manifest["metrics"]), manifest["base"], manifest["chunk_size"]
        if manifest["mechanism"] != args.name:
            raise InvalidParameters("name", args.name, f"{args.output} holds a sweep of {manifest['mechanism']}")
    else:
        space = _space(args)
        study = Study(law=args.law, samples=args.samples, period=args.period, amplitude=args.amplitude,
                      scene=args.scene)
        metrics, base, size = tuple(args.metric or ()) or None, overrides(args.set), args.chunk_size
    with tqdm(total=len(space.designs()), unit="design", file=sys.stderr, disable=args.quiet) as bar:
        summary = engine.sweep(args.name, space, args.output, study, metrics, base=base, resume=args.resume,
                               scheduler=args.scheduler, workers=args.workers, chunk_size=size,
                               fast=not args.xacro, progress=bar.update)
    counts = ", ".join(f"{k} {v}" for k, v in sorted(summary.statuses.items()))
    print(f"{summary.designs} designs ({summary.evaluated} evaluated now) on {summary.workers} workers in "
          f"{summary.seconds:.1f} s: {counts} -> {summary.out}")
    if args.optimise:
        from mechkit.sweep.optimise import optimise

        for r in optimise(args.output, args.optimise, starts=args.starts, maximise=args.maximise,
                          max_evaluations=args.evaluations, scheduler=args.scheduler, workers=args.workers):
            print(f"{args.optimise}: {r.start_value:.6g} at {_show(r.start)} -> {r.value:.6g} at {_show(r.best)} "
                  f"({r.evaluations} evaluations; {r.message})")


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `sweep`."""
    p = sub.add_parser("sweep", help="evaluate many designs on Dask (Parquet results, resumable)", **examples(
        "mechkit sweep four_bar --grid crank=0.08:0.12:5 --grid coupler=0.26:0.30:5 -o sweep_fb",
        "mechkit sweep five_bar --lhs 200 --grid dist1=0.2:0.25 --grid dist2=0.2:0.25 -o sweep_5b --resume"))
    p.add_argument("name", help="mechanism name (see `mechkit list`)")
    p.add_argument("--grid", action="append", metavar="NAME=LO:HI[:N]",
                   help="a swept parameter: N grid values from LO to HI (bounds only with --random/--lhs)")
    p.add_argument("--random", type=int, default=0, metavar="N", help="N designs drawn uniformly in the bounds")
    p.add_argument("--lhs", type=int, default=0, metavar="N", help="N designs of a Latin hypercube in the bounds")
    p.add_argument("--seed", type=int, default=0, help="seed of --random / --lhs (default 0)")
    p.add_argument("--set", action="append", metavar="NAME=VALUE", help="fix a parameter of every design")
    p.add_argument("--metric", action="append", help="a metric to measure (repeatable; default: the mechanism's set)")
    p.add_argument("--scene", help="run the mechanism's scene as the motion (default: the --law)")
    p.add_argument("--law", default="swing", choices=("swing", "turn"), help="input law (default swing)")
    p.add_argument("--samples", type=int, default=100, help="instants of the motion study (default 100)")
    p.add_argument("--period", type=float, default=1.0, help="duration of the motion, s (default 1)")
    p.add_argument("--amplitude", type=float, default=0.3, help="swing amplitude, rad or m (default 0.3)")
    p.add_argument("-o", "--output", required=True, help="results folder (a Parquet dataset)")
    p.add_argument("--resume", action="store_true", help="continue the sweep in the results folder")
    p.add_argument("--scheduler", help="address of a running Dask scheduler (default: $MECHKIT_DASK_SCHEDULER, "
                   "else an embedded local cluster)")
    p.add_argument("--workers", type=int, help="workers of the embedded cluster (default: the CPU count)")
    p.add_argument("--chunk-size", type=int, help="designs per task (default: about 4 tasks per worker)")
    p.add_argument("--xacro", action="store_true", help="build every design through xacro (not the template cache)")
    p.add_argument("--optimise", metavar="COLUMN", help="then refine this metric column from the best designs "
                   "(scipy.optimize, evaluations on the same engine)")
    p.add_argument("--maximise", action="store_true", help="maximise the --optimise column (default: minimise)")
    p.add_argument("--starts", type=int, default=2, help="searches started from the best designs (default 2)")
    p.add_argument("--evaluations", type=int, default=60, help="evaluations per search (default 60)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)
