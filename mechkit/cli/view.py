"""`mechkit view`: a live meshcat viewer of a mechanism (a pose, or a scene playing), open until Ctrl-C."""

from __future__ import annotations

import argparse
import time

from mechkit.cli.common import (
    add_mechanism_arguments,
    add_mesh_path_argument,
    assembly_line,
    examples,
    load_mechanism,
    mesh_search,
)


def run(args: argparse.Namespace) -> None:
    """Start the viewer, say where it is, and keep it open until Ctrl-C (or until its server ends).

    Args:
        args: the parsed command line.
    """
    try:
        viewer, home = _start(args)
    except KeyboardInterrupt:
        print("stopped", flush=True)
        return
    try:
        print(f"meshcat viewer of {args.name} at {viewer.url} (Ctrl-C to stop)", flush=True)
        print(assembly_line(home), flush=True)
        while viewer.running:
            time.sleep(0.2)
        print("the meshcat server stopped", flush=True)
    except KeyboardInterrupt:
        print("stopped", flush=True)  # said at once, whatever closing the server takes
    finally:
        viewer.close()


def _start(args: argparse.Namespace):
    """Load the mechanism (a registered name or a file) and start a viewer showing it; meshes are looked
    for beside the file, then in the --mesh-path folders. Returns the viewer and the home assembly."""
    from mechkit.viz.live import view

    mech = load_mechanism(args)
    return view(mech, scene=args.scene, meshes=mesh_search(args)), mech.home_assembly


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `view`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "view",
        help="live meshcat viewer (a browser page) of a pose or a playing scene",
        **examples(
            "mechkit view four_bar --scene sweep",
            "mechkit view robot.urdf --mesh-path ~/ros/src --actuated shoulder,elbow",
        ),
    )
    add_mechanism_arguments(p)
    p.add_argument("--scene", help="play a scene of the mechanism (see `mechkit.scenes`); default: its home pose")
    add_mesh_path_argument(p)
    p.set_defaults(func=run)
