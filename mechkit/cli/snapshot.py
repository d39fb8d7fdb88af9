"""`mechkit snapshot`: self-contained meshcat HTML (and PNG) of a pose or a scene."""

from __future__ import annotations

import argparse

from mechkit.cli import option_values
from mechkit.cli.common import (
    add_mechanism_arguments,
    add_mesh_path_argument,
    examples,
    load_mechanism,
    mesh_search,
)


def run(args: argparse.Namespace) -> None:
    """Write the page (and the screenshot) and say where.

    Args:
        args: the parsed command line.
    """
    from mechkit.viz import snapshot_command

    q = None if args.q is None else option_values.numbers("--q", args.q, what="input values separated by commas")
    option_values.suffixed("-o", args.output, (".html",))
    option_values.suffixed("--png", args.png, (".png",))
    for path in snapshot_command(
        load_mechanism(args), q=q, scene=args.scene, html=args.output, png=args.png, meshes=mesh_search(args)
    ):
        print(f"wrote {path}")


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `snapshot`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "snapshot",
        help="self-contained meshcat HTML (and PNG) of a pose or an animated scene",
        **examples(
            "mechkit snapshot four_bar --q 0.8 -o four_bar.html",
            "mechkit snapshot ten_bar --scene deploy -o deploy.html --png deploy.png",
        ),
    )
    add_mechanism_arguments(p)
    p.add_argument("--q", help="input coordinates, comma-separated, in actuated order (rad or m)")
    p.add_argument("--scene", help="animate a scene of the mechanism (see `mechkit.scenes`), instead of one pose")
    p.add_argument("-o", "--output", help="HTML file to write")
    p.add_argument("--png", help="PNG screenshot to write (needs a headless Chromium)")
    add_mesh_path_argument(p)
    p.set_defaults(func=run)
