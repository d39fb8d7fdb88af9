"""`mechkit modes`: natural frequencies and mode shapes, actuators locked, optionally one mode animated."""

from __future__ import annotations

import argparse

from mechkit.base.exceptions import InvalidArgument
from mechkit.base.json_text import dumps
from mechkit.cli import option_values
from mechkit.cli.common import add_mechanism_arguments, examples, load_mechanism
from mechkit.cli.stiffness import pose


def report(args: argparse.Namespace) -> dict:
    """The modes as the JSON contract: frequencies (Hz), and each mode's largest body motion.

    Args:
        args: the parsed command line (`-n`, `--at`, `--animate`, `--mode`).

    Returns:
        {"name", "modes": [{"mode", "frequency_hz", "largest_motion_body", "near_mechanism"}], "animation":
        the page written, or None}; near_mechanism: below a gap (`mechkit.elastic.modes`).

    Raises:
        InvalidArgument: `-n` below 1, `--mode` not among the modes or without `--animate`, `--animate` not
            an .html file.
    """
    from mechkit.elastic import ElasticModel

    if args.n < 1:
        raise InvalidArgument("-n", args.n, "must be at least 1")
    if args.mode is not None and args.animate is None:  # it chooses what the animation shows
        raise InvalidArgument("--mode", args.mode, "chooses the mode --animate shows: give --animate too")
    mode = 1 if args.mode is None else args.mode
    if args.animate is not None and not 1 <= mode <= args.n:
        raise InvalidArgument("--mode", mode, f"must be one of the {args.n} modes computed (-n)")
    option_values.suffixed("--animate", args.animate, (".html",))
    mech = load_mechanism(args)
    q = pose(mech, args.at)
    modes = ElasticModel(mech).modes(q, args.n)
    if args.animate:
        from mechkit.elastic.animation import write_mode_page

        write_mode_page(mech, q, modes, mode - 1, args.animate)
    out = []
    for k, f in enumerate(modes.frequencies):
        shape = modes.shapes[k]
        body = int(abs(shape[:, :3]).sum(axis=1).argmax())
        out.append(
            {
                "mode": k + 1,
                "frequency_hz": float(f),
                "largest_motion_body": modes.names[body],
                "near_mechanism": bool(modes.near_mechanism[k]),
            }
        )
    return {"name": mech.spec.name, "modes": out, "animation": args.animate}


def run(args: argparse.Namespace) -> None:
    """Print the modes (text, or the JSON contract with `--json`).

    Args:
        args: the parsed command line.
    """
    from mechkit.elastic.modes import NEAR_MECHANISM

    r = report(args)
    if args.json:
        print(dumps(r, indent=2))
        return
    print(f"{r['name']}: natural frequencies, actuators locked")
    for m in r["modes"]:
        near = (
            f" - near-mechanism (below a gap: a frequency under {NEAR_MECHANISM:g} of the next)"
            if m["near_mechanism"]
            else ""
        )
        print(f"  mode {m['mode']}: {m['frequency_hz']:.4g} Hz (largest motion: {m['largest_motion_body']}){near}")
    if r["animation"]:
        print(f"wrote {r['animation']}")


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `modes`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "modes",
        help="natural frequencies and mode shapes (elastic links, locked actuators)",
        **examples("mechkit modes deployable_9rr12uru -n 6", "mechkit modes parallel_2t1r --animate mode1.html --json"),
    )
    add_mechanism_arguments(p)
    p.add_argument("-n", type=int, default=6, help="number of modes (default 6)")
    p.add_argument("--at", metavar="J=V,...", help="the pose's input joints (rad or m; default the home pose)")
    p.add_argument("--animate", metavar="F.html", help="write an animation of one mode (offline meshcat page)")
    p.add_argument("--mode", type=int, help="the mode --animate shows (default 1)")
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(func=run)
