"""`mechkit stiffness`: the 6x6 stiffness and compliance of a body at a point and pose, actuators locked."""

from __future__ import annotations

import argparse

import numpy as np

from mechkit.base.json_text import dumps, nulls
from mechkit.cli import option_values
from mechkit.cli.common import add_mechanism_arguments, examples, load_mechanism
from mechkit.core import refuse_outside
from mechkit.mechanism import Mechanism

DIRECTIONS = ("x", "y", "z", "rx", "ry", "rz")
#: Why an axis has no finite stiffness (`mechkit.elastic.body_stiffness`).
RIGID_AXIS = "held rigidly: no elastic element yields along it (or it is stiffer than the computation resolves)"


def pose(mech: Mechanism, text: str | None) -> np.ndarray:
    """The assembled pose of `--at J=V,...`.

    Args:
        mech: the mechanism.
        text: the option's text, joint=value pairs (rad or m); None or empty: the home pose.

    Returns:
        (nq,) the configuration, every loop closed.

    Raises:
        InvalidArgument: a pair without "=", a value that is not a finite number, a joint given twice.
        OutsideLimits: the pose's branch leaves a joint's limits.
    """
    if not text:
        return mech.home_q
    given = option_values.named_numbers("--at", text.split(","), "JOINT=VALUE pairs separated by commas", 1)
    at = mech.assembly({joint: values[0] for joint, values in given.items()})
    refuse_outside(mech.model, at, f"--at {text}")
    return at.q


def report(args: argparse.Namespace) -> dict:
    """The stiffness as the JSON contract: body, point (world, m), compliance and stiffness (6x6, SI; the
    stiffness off the rigid directions), the directions held rigidly, held (K_ii) and free (1/C_ii) per
    direction (null for an axis held rigidly, with the reason under `held_why` / `free_why`).

    Args:
        args: the parsed command line (`--body`, `--point`, `--at`).

    Returns:
        The report.
    """
    from mechkit.elastic import ElasticModel

    mech = load_mechanism(args)
    e = ElasticModel(mech)
    q = pose(mech, args.at)
    point = None if args.point is None else np.array(option_values.numbers("--point", args.point, 3, what="X,Y,Z"))
    s = e.stiffness(q, args.body, point)
    held, held_why = nulls(dict(zip(DIRECTIONS, s.held)), RIGID_AXIS)
    free, free_why = nulls(dict(zip(DIRECTIONS, s.free)), RIGID_AXIS)
    return {
        "name": mech.spec.name,
        "body": s.body,
        "point": s.point.tolist(),
        "compliance": s.compliance.tolist(),
        "stiffness": s.stiffness.tolist(),
        "rigid_directions": s.rigid.T.tolist(),
        "held": held,
        "held_why": held_why,
        "free": free,
        "free_why": free_why,
    }


def format_text(r: dict) -> str:
    """K_ii and 1/C_ii per direction for a reader ("rigid" where a direction is held rigidly).

    Args:
        r: what `report` gave.

    Returns:
        The text, lines joined.
    """
    lines = [
        f"{r['name']}: body {r['body']} at ({', '.join(f'{x:.4f}' for x in r['point'])}) m, world axes",
        f"{'direction':>9} {'K_ii (others held)':>20} {'1/C_ii (others free)':>22}",
    ]
    for d in DIRECTIONS:
        unit = "N/m" if len(d) == 1 else "N m/rad"
        held, free = (
            f"{v:>16.4g} {unit:<7}" if v is not None else f"{'rigid':>16} {'':<7}" for v in (r["held"][d], r["free"][d])
        )
        lines.append(f"{d:>9} {held} {free}".rstrip())
    if r["rigid_directions"]:
        lines.append(f"rigid: {len(r['rigid_directions'])} direction(s) {RIGID_AXIS}")
    return "\n".join(lines)


def run(args: argparse.Namespace) -> None:
    """Print the stiffness (text, or the JSON contract with `--json`).

    Args:
        args: the parsed command line.
    """
    r = report(args)
    print(dumps(r, indent=2) if args.json else format_text(r))


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `stiffness`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "stiffness",
        help="6x6 stiffness and compliance of a body (elastic links, locked actuators)",
        **examples(
            "mechkit stiffness parallel_2t1r --body platform",
            "mechkit stiffness four_bar --body coupler_link --point 0.14,0,0 --at crank=0.8 --json",
        ),
    )
    add_mechanism_arguments(p)
    p.add_argument("--body", required=True, help="the body's URDF link")
    p.add_argument("--point", metavar="X,Y,Z", help="the point in the link's frame (m; default its origin)")
    p.add_argument("--at", metavar="J=V,...", help="the pose's input joints (rad or m; default the home pose)")
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(func=run)
