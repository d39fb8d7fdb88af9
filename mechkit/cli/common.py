"""What several commands share: the mechanism argument (a name or a file) and its overrides."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from mechkit.base.exceptions import ClosureNotConverged, InvalidArgument, MechkitError
from mechkit.cli import option_values
from mechkit.core import Assembly, refuse_outside, wrap_into_limits
from mechkit.loading import load
from mechkit.mechanism import Mechanism

if TYPE_CHECKING:
    from mechkit.viz.meshes import MeshSearch


def examples(*commands: str) -> dict[str, Any]:
    """`add_parser` keywords ending a command's `--help` with its examples (one command line each).

    Args:
        commands: command lines, each a working example.

    Returns:
        `epilog` and `formatter_class` keywords for `add_parser`.
    """
    return {
        "epilog": "examples:\n" + "\n".join(f"  {c}" for c in commands),
        "formatter_class": argparse.RawDescriptionHelpFormatter,
    }


def add_mechanism_arguments(parser: argparse.ArgumentParser) -> None:
    """The positional NAME or PATH, the repeatable `--set NAME=VALUE` and `--actuated`.

    Args:
        parser: a command's parser.
    """
    parser.add_argument(
        "name",
        metavar="NAME|PATH",
        help="registered mechanism (see `mechkit list`) or a file: .urdf with <mechkit:loop>s (and "
        "<mimic> joints), with a .yaml sidecar (Extended URDF) or with URDF+ <loop>/<coupling>s; "
        ".xacro; MJCF .xml; SDFormat .sdf",
    )
    parser.add_argument(
        "--set",
        action="append",
        metavar="NAME=VALUE",
        help="override a parameter (SI units, rad) or pass a xacro argument to a .xacro file; "
        "rows=spatial closes every cut with its full rows",
    )
    parser.add_argument("--actuated", metavar="J1,J2", help="actuated joints, overriding what the file declares")
    parser.add_argument(
        "--lock",
        action="append",
        metavar="JOINT=VALUE",
        help="lock a joint at a value (rad or m; a ball or free joint: comma-separated values); repeatable",
    )
    parser.add_argument(
        "--keep", metavar="B1,B2", help="keep only the subsystem of these bodies; lock every other joint at home"
    )
    parser.add_argument(
        "--fix", metavar="BODY", action="append", help="lock a body's own joint at home (a floating root); repeatable"
    )
    parser.add_argument(
        "--ignore-unknown-closures",
        action="store_true",
        help="load a file holding another tool's loop closures mechkit does not read (Drake constraints and "
        "bushings, Gazebo joints) as its tree without them, one warning per element (default: refused)",
    )
    parser.add_argument(
        "--bushings",
        choices=("rigid", "compliant"),
        default="rigid",
        help="Drake bushings as the cuts their stiff directions make (rigid, the default) or as compliant force "
        "elements the simulator applies (a URDF's or xacro's)",
    )
    parser.add_argument(
        "--freeflyer",
        action="store_true",
        help="put an Extended-URDF file's tree on a free-flyer root joint (as Gepetto's loader can)",
    )


def add_base_arguments(parser: argparse.ArgumentParser, motion: bool = True) -> None:
    """`--base`, `--base-inertia` and (with `motion`) `--base-motion` (`mechkit.bases`).

    Args:
        parser: a command's parser.
        motion: also take a moving base's motion from a CSV file.
    """
    parser.add_argument(
        "--base",
        choices=("fixed", "moving", "floating"),
        default="fixed",
        help="the ground: fixed (the world), moving (carried by --base-motion) or floating (a free bus)",
    )
    parser.add_argument(
        "--base-inertia", metavar="MASS,IXX,IYY,IZZ", help="the base body's mass (kg) and moments (kg m^2)"
    )
    if motion:
        parser.add_argument(
            "--base-motion",
            metavar="BASE.csv",
            help="a moving base's motion: CSV of t,x,y,z,roll,pitch,yaw (s, m, rad); its times are the run's",
        )


def carried_inputs(mech: Mechanism, args: argparse.Namespace, inputs: Any = None) -> Any:
    """The input law with a moving base's motion (`--base-motion`) joined to the inputs' law.

    Args:
        mech: the mechanism (on the base the command line asked).
        args: the parsed command line.
        inputs: the inputs' law (`mechkit.motion.InputLaw`) on the base motion's times, or None (held at home).

    Returns:
        The joined law, or `inputs` when no base motion is given.

    Raises:
        InvalidArgument: --base-motion without --base moving, or a law on other times.
    """
    path = getattr(args, "base_motion", None)
    if path is None:
        return inputs
    if getattr(args, "base", "fixed") != "moving":
        raise InvalidArgument("--base-motion", path, "moves a base: give --base moving too")
    from mechkit import bases

    return bases.carried(mech, bases.from_csv(path), inputs)


def overrides(pairs: list[str] | None) -> dict[str, str]:
    """`--set` pairs as a dict.

    Args:
        pairs: the NAME=VALUE strings given, if any.

    Returns:
        Name -> value (a string; the parameter class converts it).

    Raises:
        InvalidArgument: a pair without "=" or with an empty side, a name given twice.
    """
    return option_values.pairs("--set", pairs, empty=True)


def actuated(text: str | None) -> list[str] | None:
    """`--actuated J1,J2` as a list of joint names (None when not given).

    Args:
        text: the option's value, if given.

    Returns:
        The joint names, or None.

    Raises:
        InvalidArgument: an empty name, or a name given twice.
    """
    return None if text is None else option_values.names("--actuated", text)


def locks(pairs: list[str] | None) -> dict[str, float | list[float]] | None:
    """`--lock JOINT=VALUE` pairs (a value, or comma-separated values for a joint of several freedoms).

    Args:
        pairs: the --lock arguments, or None.

    Returns:
        joint -> value(s), or None when none is given.

    Raises:
        InvalidArgument: a pair without '=', a value that is not a finite number, a joint given twice.
    """
    if not pairs:
        return None
    given = option_values.named_numbers("--lock", pairs, "JOINT=VALUE (comma-separated values for a ball joint)")
    return {joint: values[0] if len(values) == 1 else values for joint, values in given.items()}


def load_mechanism(args: argparse.Namespace) -> Mechanism:
    """The mechanism the command line names, with its overrides and reductions.

    Args:
        args: the parsed command line (name, --set, --actuated, --lock, --keep, --fix, --freeflyer, --base,
            --base-inertia).

    Returns:
        The mechanism.

    Raises:
        InvalidArgument: a malformed --set, --actuated or --lock.
        MechkitError: what `mechkit.load` refuses; a home assembly that does not close names the source.
    """
    keep = None if getattr(args, "keep", None) is None else option_values.names("--keep", args.keep)
    try:
        mech = load(
            args.name,
            actuated=actuated(args.actuated),
            lock=locks(getattr(args, "lock", None)),
            keep=keep,
            fix=getattr(args, "fix", None),
            freeflyer=getattr(args, "freeflyer", False),
            ignore_unknown_closures=getattr(args, "ignore_unknown_closures", False),
            bushings=getattr(args, "bushings", "rigid"),
            base=getattr(args, "base", "fixed"),
            base_inertia=_base_inertia(getattr(args, "base_inertia", None)),
            **overrides(args.set),
        )
    except ClosureNotConverged as err:
        raise MechkitError(f"{args.name}: its loops do not close at home: {err}") from None
    return mech


def _base_inertia(text: str | None) -> tuple[float, list[float]] | None:
    if text is None:
        return None
    mass, *moments = option_values.numbers("--base-inertia", text, 4, what="MASS,IXX,IYY,IZZ")
    return mass, moments


def assembly_line(assembly: Assembly, what: str = "the home assembly") -> str:
    """The line saying which branch an assembly took and whether it stays in the joints' limits.

    Args:
        assembly: the assembly (`Mechanism.assembly`, `Mechanism.home_assembly`).
        what: which assembly it is.

    Returns:
        "assembly: <what>, <branch>; <limits>".
    """
    limits = f"outside their limits: {', '.join(assembly.outside)}" if assembly.outside else "within the joint limits"
    return f"assembly: {what}, {assembly.branch}; {limits}"


def refuse_path_outside(mech: Mechanism, q: np.ndarray, t: np.ndarray, what: str) -> None:
    """Refuse a path (each sample continued from the previous one) whose branch leaves a loop joint's limits.

    Args:
        mech: the mechanism.
        q: (N, nq) the samples (rows of NaN: samples that failed, skipped).
        t: (N,) their times, s.
        what: the path, for the message.

    Raises:
        OutsideLimits: at the first sample with a loop joint outside its limits (no whole turn brings it in).
    """
    for qk, tk in zip(q, t):
        if np.all(np.isfinite(qk)):
            _, outside = wrap_into_limits(mech.model, qk)
            on_loops = tuple(j for j in outside if mech.joint_id(j) in mech.closure_model.on_loops)
            at = Assembly(qk, 0, 0.0, "continued from the previous sample", on_loops)
            refuse_outside(mech.model, at, f"{what} at t = {tk:.6g} s")


def add_mesh_path_argument(parser: argparse.ArgumentParser) -> None:
    """The repeatable `--mesh-path DIR` (folders searched for a URDF's mesh files).

    Args:
        parser: a command's parser.
    """
    parser.add_argument(
        "--mesh-path",
        action="append",
        metavar="DIR",
        help="folder searched for mesh files and package:// addresses, after the file's own (repeatable)",
    )


def mesh_search(args: argparse.Namespace) -> MeshSearch:
    """Where the drawing looks for mesh files (`mechkit.viz.meshes.MeshSearch`): beside the file the
    command line names (if it names a file), then in the `--mesh-path` folders.

    Args:
        args: the parsed command line (name, --mesh-path).

    Returns:
        The search.
    """
    from mechkit.viz.meshes import MeshSearch

    path = Path(args.name).expanduser()
    return MeshSearch.of(path.resolve().parent if path.is_file() else None, args.mesh_path or ())


def check_writers(table: str | None, plot: str | None, what: str) -> None:
    """Refuse, before any work, a `-o` table or a `--plot` that cannot be written or whose library is
    missing (pandas, and pyarrow for Parquet; matplotlib).

    Args:
        table: the table's file (.parquet or .csv), or None.
        plot: the plot's file, or None.
        what: what the plot is, for the error.

    Raises:
        OutputError: a file that cannot be written (a directory, a device, ...).
        MethodUnavailable: the library is not installed (the message says what to install).
    """
    from mechkit.base.atomic import resolve_output
    from mechkit.base.plotting import pyplot
    from mechkit.history import result

    if table:
        resolve_output(table)
        result.pandas()
        if Path(table).suffix.lower() == ".parquet":
            result.pyarrow()
    if plot:
        resolve_output(plot)
        pyplot(what)
