"""`mechkit motion`: efforts and every joint's reaction along a motion; the peak table, Parquet or CSV,
and a plot."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from mechkit.base.exceptions import InvalidArgument, MotionFailed
from mechkit.base.joint_arguments import joint_names
from mechkit.cli import option_values
from mechkit.cli.common import (
    add_base_arguments,
    add_mechanism_arguments,
    assembly_line,
    carried_inputs,
    check_writers,
    examples,
    load_mechanism,
    refuse_path_outside,
)
from mechkit.cli.progress import ProgressBars
from mechkit.cli.simulate import PLOT_SUFFIXES

if TYPE_CHECKING:
    from mechkit.history.result import MotionResult

#: Motions of at least this many samples show a progress bar (`mechkit.cli.progress`: stderr, on a terminal).
LONG_MOTION = 100
#: --hold's target: the body's z axis along the world's (level).
LEVEL = ((0.0, 0.0, 1.0), (0.0, 0.0, 1.0))
#: Peak-table columns: header, quantity.
PEAK_COLUMNS = (
    ("|f| N", "force"),
    ("axial N", "axial_force"),
    ("radial N", "radial_force"),
    ("|m| N m", "moment"),
    ("axial N m", "axial_moment"),
    ("radial N m", "radial_moment"),
)


def format_peaks(result: MotionResult) -> list[str]:
    """The peak table: one line per joint, each peak with its time.

    Args:
        result: the study.

    Returns:
        Text lines: a header, one line per joint (whether it is a support, each peak and its time; "-" for the
            axial and radial parts of a joint without an axis), and notes for those and for components that are
            statically indeterminate.
    """
    from mechkit.motion import peaks

    rows = peaks(result)
    width = max(len("joint"), *(len(p.joint) for p in rows))
    head = f"{'joint':<{width}} sup " + " ".join(f"{h:>11} {'t (s)':>7}" for h, _ in PEAK_COLUMNS)
    lines = [head]
    for p in rows:
        cells = " ".join(
            f"{p.values[q]:11.4g} {p.times[q]:7.3f}" if math.isfinite(p.values[q]) else f"{'-':>11} {'-':>7}"
            for _, q in PEAK_COLUMNS
        )
        mark = " *" if p.determinate is False else ""
        lines.append(f"{p.joint:<{width}} {'yes' if p.support else 'no ':>3} {cells}{mark}")
    if any(not math.isfinite(p.values[q]) for p in rows for _, q in PEAK_COLUMNS):
        lines.append("- no axial or radial part: the joint has no axis (a ball or free joint)")
    if any(p.determinate is False for p in rows):
        lines.append("* some components statically indeterminate (redundant constraints): minimum-norm values")
    return lines


def run(args: argparse.Namespace) -> None:
    """Run the study, print the peak table, write what was asked.

    Args:
        args: the parsed command line.

    Raises:
        InvalidArgument: an output that is neither .parquet nor .csv, a plot of a format not written, a
            malformed --joints, or --joints without --plot; --hold without --base moving --base-motion.
        InvalidParameters: an output that cannot be written or whose library is missing.
        MotionFailed: no sample of the motion succeeded.
        OutsideLimits: the motion's branch leaves a loop joint's limits (named with its time).
    """
    from mechkit import motion
    from mechkit.motion.plot import write_plot

    option_values.suffixed("-o", args.output, (".parquet", ".csv"))
    option_values.suffixed("--plot", args.plot, PLOT_SUFFIXES)
    joints = option_values.names("--joints", args.joints) if args.joints else None
    if joints and not args.plot:  # it chooses what the plot shows: without one it would be ignored
        raise InvalidArgument("--joints", args.joints, "chooses the joints --plot shows: give --plot too")
    mech = load_mechanism(args)
    if joints:
        joint_names("--joints", joints, mech.closure_model.joint_names)
    if args.hold is not None:
        result, source = _held(mech, args)
    else:
        result, source = _studied(mech, args)
    if len(result.failures) == len(result.t):
        raise MotionFailed(result.failures)
    refuse_path_outside(mech, result.q, result.t, f"{mech.spec.name}: the motion")
    print(f"{mech.spec.name}: {source}, {len(result.t)} samples, t = {result.t[0]:.6g} .. {result.t[-1]:.6g} s")
    print(f"{assembly_line(mech.home_assembly)}; each sample continued from the previous sample")
    for t, why in result.failures:
        print(f"skipped t = {t:.6g} s: {why}")
    print("peak reactions (world frame; axial/radial along the joint axis):")
    print("\n".join(format_peaks(result)))
    if args.output:
        parquet = Path(args.output).suffix.lower() == ".parquet"  # the suffix was checked in any case
        writer = motion.write_parquet if parquet else motion.write_csv
        print(f"wrote {writer(result, args.output)}")
    if args.plot:
        print(f"wrote {write_plot(result, args.plot, joints)}")


def _studied(mech, args: argparse.Namespace) -> tuple[Any, str]:
    """The study of the law the command line gives (--inputs, --scene, a --base-motion joined to them) and
    the law's source."""
    from mechkit import motion

    if args.inputs:
        law = motion.from_csv(mech, args.inputs)
    else:
        scene = args.scene or next(iter(mech.spec.scenes), "sweep")
        law = motion.from_scene(mech, scene)
    if args.base_motion:  # the carrier's motion sets the times: the inputs on them, else held at home
        law = carried_inputs(mech, args, law if args.inputs else None)
    if args.samples is not None:
        law = motion.resample(law, args.samples)
    check_writers(args.output, args.plot, "motion plots")
    bars = ProgressBars(None if len(law.t) >= LONG_MOTION else False)
    result = motion.study(
        mech,
        law,
        determinacy=args.determinacy,
        skip_failures=True,
        progress=lambda done, total: bars(f"{mech.spec.name} motion", done, total),
    )
    return result, law.source


def _held(mech, args: argparse.Namespace) -> tuple[Any, str]:
    """--hold: the inputs keeping a body level (its z axis along the world's) along --base-motion, and their
    study (`mechkit.bases.held_motion`); the source line says the largest tilt left."""
    from mechkit import bases

    if args.base_motion is None or args.base != "moving":
        raise InvalidArgument("--hold", args.hold, "holds a body while a base moves: give --base moving --base-motion")
    if args.inputs or args.scene or args.samples is not None:
        raise InvalidArgument("--hold", args.hold, "finds the inputs itself: not with --inputs, --scene or --samples")
    check_writers(args.output, args.plot, "motion plots")
    held = bases.held_motion(mech, bases.from_csv(args.base_motion), args.hold, LEVEL)
    tilt = float(np.max(np.abs(held.tilt)))
    return held.study, f"{args.hold} held level on {args.base_motion} (tilt left <= {tilt:.2g} rad)"


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `motion`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "motion",
        help="efforts and every joint's reaction along a motion: peak table, Parquet/CSV, plot",
        **examples(
            "mechkit motion parallel_2t1r --scene motion_law --samples 501 -o law.parquet --plot law.png",
            "mechkit motion four_bar --inputs crank.csv -o loads.csv",
        ),
    )
    add_mechanism_arguments(p)
    add_base_arguments(p)
    source = p.add_mutually_exclusive_group()
    source.add_argument("--scene", help="a scene of the mechanism (default: its first declared scene, else 'sweep')")
    source.add_argument(
        "--inputs",
        metavar="LAW.csv",
        help="CSV of t (s) and one column per driven joint (rad or m); optional <joint>_dot, <joint>_ddot",
    )
    source.add_argument(
        "--hold",
        metavar="BODY",
        help="with --base moving --base-motion: the inputs that keep BODY level (its z axis vertical) as the "
        "carrier moves, and their efforts and reactions",
    )
    p.add_argument("--samples", type=int, help="resample the law at N uniform times")
    p.add_argument("-o", "--output", help="write the table: .parquet or .csv")
    p.add_argument("--plot", help="write a plot of efforts and reactions (.png, .svg, .pdf)")
    p.add_argument("--joints", help="comma-separated joints whose reactions the plot shows (default: the 4 busiest)")
    p.add_argument("--determinacy", action="store_true", help="flag the reaction components equilibrium fixes")
    p.set_defaults(func=run)
