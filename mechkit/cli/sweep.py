"""`mechkit sweep`: evaluate many designs of a mechanism on Dask, one Parquet row per design.

Exit status: 0 done; 2 an error in the arguments (or anything else mechkit refuses); 3 to 6 (the
`EXIT_*` constants) when the cluster cannot finish the sweep: then one line on stderr says why, how
many designs are saved and the command that resumes, and the details (Dask's own log records, the
traceback) are in the results folder's `sweep.log`.
"""

from __future__ import annotations

import argparse
import shlex
import sys
from collections.abc import Callable
from typing import TYPE_CHECKING, NoReturn

from mechkit.base.exceptions import InvalidArgument, InvalidParameters
from mechkit.cli import option_values
from mechkit.cli.common import examples, overrides

if TYPE_CHECKING:
    from tqdm import tqdm

    from mechkit.sweep.cluster import ClusterState

#: The scheduler could not be reached (down, wrong address, or it refused the client, e.g. tcp:// to a TLS one).
EXIT_UNREACHABLE = 3
#: No worker served the cluster for --wait-workers seconds (at the start, or after the workers went).
EXIT_NO_WORKERS = 4
#: The scheduler was lost mid-sweep (killed, stopped, or the network to it went down).
EXIT_SCHEDULER_LOST = 5
#: A task failed on the cluster itself (its workers died running it, or mechkit is not importable there).
EXIT_TASK_FAILED = 6
#: The refinement's searches (--starts) and evaluations per search (--evaluations) unless given.
STARTS, EVALUATIONS = 2, 60


def _space(args: argparse.Namespace):
    from mechkit.sweep.space import DesignSpace, parse_axis

    if args.random and args.lhs:
        raise InvalidParameters("random/lhs", (args.random, args.lhs), "choose one sampling: --random N or --lhs N")
    mode, count = ("random", args.random) if args.random else ("lhs", args.lhs) if args.lhs else ("grid", 0)
    return DesignSpace(tuple(parse_axis(a) for a in args.grid or []), mode, count, args.seed)


def _or(value: int | None, default: int) -> int:
    return default if value is None else value


def _refinement_options(args: argparse.Namespace) -> None:
    """Refuse an option of the refinement given without --optimise: it would be ignored."""
    if args.optimise:
        return
    for option, value in (
        ("--maximise", args.maximise),
        ("--starts", args.starts),
        ("--evaluations", args.evaluations),
    ):
        if value not in (None, False):
            raise InvalidArgument(option, value, "tunes the refinement: give --optimise COLUMN too")


def _show(design: dict[str, float]) -> str:
    return ", ".join(f"{k}={v:.6g}" for k, v in design.items())


def _stop(message: str, status: int) -> NoReturn:
    """End the command: `message` on one line of stderr, as `mechkit.cli.main` prints errors; exit `status`."""
    print(f"mechkit: error: {message}", file=sys.stderr)
    raise SystemExit(status)


def _resume_command(args: argparse.Namespace, address: str | None) -> str:
    """The command that resumes this sweep: the results folder and how it reaches its cluster."""
    words = ["mechkit", "sweep", args.name, "-o", args.output, "--resume"]
    options = {
        "--scheduler": address,
        "--tls-ca": args.tls_ca,
        "--tls-cert": args.tls_cert,
        "--tls-key": args.tls_key,
        "--workers": args.workers,
        "--wait-workers": args.wait_workers,
        "--optimise": args.optimise,
    }
    words += [
        w
        for flag, value in options.items()
        if value is not None
        for w in (flag, f"{value:g}" if isinstance(value, float) else str(value))
    ]
    flags = {"--xacro": args.xacro, "--dashboard": args.dashboard, "--maximise": args.maximise and args.optimise}
    words += [flag for flag, on in flags.items() if on]
    if args.optimise:
        words += ["--starts", str(_or(args.starts, STARTS)), "--evaluations", str(_or(args.evaluations, EVALUATIONS))]
    return shlex.join(words)


def _watcher(bar: tqdm, wait: float) -> Callable[[ClusterState], None]:
    """The `ClusterState` callback: the workers on the progress line, a notice when there are none,
    the dashboard's address once."""
    dashboard_shown = False

    def watch(state: ClusterState) -> None:
        nonlocal dashboard_shown
        bar.set_postfix_str(f"{state.workers} worker{'s' if state.workers != 1 else ''}", refresh=True)
        if state.dashboard and not dashboard_shown:
            dashboard_shown = True
            bar.write(f"mechkit: Dask dashboard at {state.dashboard}", file=sys.stderr)
        if state.workers == 0:
            bar.write(
                f"mechkit: no worker serves the Dask scheduler {state.address}; waiting up to {wait:g} s "
                "for one (--wait-workers)",
                file=sys.stderr,
            )

    return watch


def run(args: argparse.Namespace) -> None:
    """Run (or resume) the sweep, with a progress bar on stderr and a summary on stdout.

    Args:
        args: the parsed command line.

    Raises:
        SystemExit: the cluster could not finish the sweep (status `EXIT_UNREACHABLE`, `EXIT_NO_WORKERS`,
            `EXIT_SCHEDULER_LOST` or `EXIT_TASK_FAILED`), after one line on stderr.
        InvalidParameters: --resume on a folder holding another mechanism's sweep, or what the engine refuses.
        InvalidArgument: a metric named twice, an --optimise column the sweep will not have, --maximise,
            --starts or --evaluations without --optimise.
    """
    import dask
    from tqdm import tqdm

    from mechkit.sweep import cluster, engine, store
    from mechkit.sweep.metrics import Study
    from mechkit.sweep.space import DesignSpace

    _refinement_options(args)
    address = cluster.scheduler_address(args.scheduler)
    tls = cluster.tls_config(address, args.tls_ca, args.tls_cert, args.tls_key)
    if args.resume and not args.grid:  # resume what the folder holds
        manifest = store.read_manifest(args.output)
        space, study = DesignSpace.from_dict(manifest["space"]), Study(**manifest["study"])
        metrics, base, size = tuple(manifest["metrics"]), manifest["base"], manifest["chunk_size"]
        if manifest["mechanism"] != args.name:
            raise InvalidParameters("name", args.name, f"{args.output} holds a sweep of {manifest['mechanism']}")
    else:
        space = _space(args)
        study = Study(
            law=args.law, samples=args.samples, period=args.period, amplitude=args.amplitude, scene=args.scene
        )
        metrics, base, size = tuple(args.metric or ()) or None, overrides(args.set), args.chunk_size
        if metrics:
            option_values.names("--metric", ",".join(metrics))
    if args.optimise:  # before the sweep runs, not after it
        columns = (
            manifest["columns"] if args.resume and not args.grid else engine.planned_columns(args.name, metrics, base)
        )
        if args.optimise not in columns:
            raise InvalidArgument("--optimise", args.optimise, f"not a column of this sweep: {', '.join(columns)}")
    wait = cluster.WAIT_WORKERS if args.wait_workers is None else args.wait_workers
    codes = {
        cluster.SchedulerUnreachable: EXIT_UNREACHABLE,
        cluster.NoWorkers: EXIT_NO_WORKERS,
        cluster.SchedulerLost: EXIT_SCHEDULER_LOST,
        cluster.TaskFailed: EXIT_TASK_FAILED,
    }
    with dask.config.set(tls):
        try:
            with tqdm(total=len(space.designs()), unit="design", file=sys.stderr, disable=args.quiet) as bar:
                summary = engine.sweep(
                    args.name,
                    space,
                    args.output,
                    study,
                    metrics,
                    base=base,
                    resume=args.resume,
                    scheduler=address,
                    workers=args.workers,
                    chunk_size=size,
                    fast=not args.xacro,
                    wait_workers=wait,
                    dashboard=args.dashboard,
                    progress=bar.update,
                    watch=_watcher(bar, wait),
                )
        except engine.SweepStopped as err:
            _stop(f"{err}; resume with: {_resume_command(args, address)}", codes[type(err.cause)])
        counts = ", ".join(f"{k} {v}" for k, v in sorted(summary.statuses.items()))
        print(
            f"{summary.designs} designs ({summary.evaluated} evaluated now) on {summary.workers} workers in "
            f"{summary.seconds:.1f} s: {counts} -> {summary.out}"
        )
        if args.optimise:
            from mechkit.sweep.optimise import optimise

            try:
                refined = optimise(
                    args.output,
                    args.optimise,
                    starts=_or(args.starts, STARTS),
                    maximise=args.maximise,
                    max_evaluations=_or(args.evaluations, EVALUATIONS),
                    scheduler=address,
                    workers=args.workers,
                )
            except cluster.ClusterError as err:
                _stop(str(err), codes[type(err)])
            for r in refined:
                print(
                    f"{args.optimise}: {r.start_value:.6g} at {_show(r.start)} -> {r.value:.6g} at {_show(r.best)} "
                    f"({r.evaluations} evaluations; {r.message})"
                )


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `sweep`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "sweep",
        help="evaluate many designs on Dask (Parquet results, resumable)",
        **examples(
            "mechkit sweep four_bar --grid crank=0.08:0.12:5 --grid coupler=0.26:0.30:5 -o sweep_fb",
            "mechkit sweep five_bar --lhs 200 --grid dist1=0.2:0.25 --grid dist2=0.2:0.25 -o sweep_5b --resume",
        ),
    )
    p.add_argument("name", help="mechanism name (see `mechkit list`)")
    p.add_argument(
        "--grid",
        action="append",
        metavar="NAME=LO:HI[:N]",
        help="a swept parameter: N grid values from LO to HI (bounds only with --random/--lhs)",
    )
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
    p.add_argument(
        "--scheduler",
        help="address of a running Dask scheduler (default: $MECHKIT_DASK_SCHEDULER, else an embedded local cluster)",
    )
    p.add_argument("--workers", type=int, help="workers of the embedded cluster (default: the CPU count)")
    p.add_argument(
        "--wait-workers",
        type=float,
        metavar="SECONDS",
        help="how long the cluster may have no worker (at the start or later) before the sweep stops, "
        "saying what is saved (default 60)",
    )
    p.add_argument(
        "--dashboard",
        action="store_true",
        help="the embedded cluster serves Dask's dashboard on 127.0.0.1 (port 8787, or a free one)",
    )
    p.add_argument(
        "--tls-ca",
        metavar="PEM",
        help="CA certificate of a tls:// scheduler (default: Dask's configuration, distributed.comm.tls.ca-file)",
    )
    p.add_argument(
        "--tls-cert",
        metavar="PEM",
        help="this client's certificate for a tls:// scheduler (default: distributed.comm.tls.client.cert)",
    )
    p.add_argument(
        "--tls-key",
        metavar="PEM",
        help="this client's private key, unless in --tls-cert's file (default: distributed.comm.tls.client.key)",
    )
    p.add_argument("--chunk-size", type=int, help="designs per task (default: about 4 tasks per worker)")
    p.add_argument("--xacro", action="store_true", help="build every design through xacro (not the template cache)")
    p.add_argument(
        "--optimise",
        metavar="COLUMN",
        help="then refine this metric column from the best designs (scipy.optimize, evaluations on the same engine)",
    )
    p.add_argument("--maximise", action="store_true", help="maximise the --optimise column (default: minimise)")
    p.add_argument("--starts", type=int, help=f"searches started from the best designs (default {STARTS})")
    p.add_argument("--evaluations", type=int, help=f"evaluations per search (default {EVALUATIONS})")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)
