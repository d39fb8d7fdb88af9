"""`mechkit view`: a live meshcat viewer of a mechanism (a pose, or a scene playing), open until Ctrl-C."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from mechkit.cli.common import overrides
from mechkit.exceptions import InvalidParameters

EXAMPLES = """examples:
  mechkit view four_bar --scene sweep
  mechkit view robot.urdf --mesh-path ~/ros/src --actuated shoulder,elbow"""


def run(args: argparse.Namespace) -> None:
    """Start the viewer, say where it is, and keep it open until Ctrl-C (or until its server ends)."""
    try:
        viewer = _start(args)
    except KeyboardInterrupt:
        print("stopped")
        return
    try:
        print(f"meshcat viewer of {args.name} at {viewer.url} (Ctrl-C to stop)", flush=True)
        while viewer.running:
            time.sleep(0.2)
        print("the meshcat server stopped")
    except KeyboardInterrupt:
        print("stopped")
    finally:
        viewer.close()


def _start(args: argparse.Namespace):
    """Load the mechanism (a registered name, or a URDF file) and start a viewer showing it."""
    from mechkit.mechanism import from_urdf, load
    from mechkit.viz.live import view
    from mechkit.viz.meshes import MeshSearch

    path = Path(args.name).expanduser()
    if path.suffix.lower() == ".urdf":
        if not path.is_file():
            raise InvalidParameters("name", args.name, "no such URDF file")
        if args.set:
            raise InvalidParameters("set", args.set, "a URDF file has no parameters to override")
        actuated = args.actuated.split(",") if args.actuated else None
        mechanism = from_urdf(path.read_text(), actuated=actuated, name=path.stem)
        meshes = MeshSearch.of(path.resolve().parent, args.mesh_path or ())
    else:
        mechanism = load(args.name, **overrides(args.set))
        meshes = MeshSearch.of(None, args.mesh_path or ())
    return view(mechanism, scene=args.scene, meshes=meshes)


def add_parser(sub) -> None:
    """Register `view`."""
    p = sub.add_parser("view", help="live meshcat viewer (a browser page) of a pose or a playing scene",
                       epilog=EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("name", help="mechanism name (see `mechkit list`) or a .urdf file")
    p.add_argument("--set", action="append", metavar="NAME=VALUE", help="override a parameter (SI units, rad)")
    p.add_argument("--scene", help="play a scene of the mechanism (see `mechkit.scenes`); default: its home pose")
    p.add_argument("--mesh-path", action="append", metavar="DIR",
                   help="folder searched for mesh files and package:// addresses (repeatable)")
    p.add_argument("--actuated", help="a URDF file's actuated joints, comma-separated (default: every joint)")
    p.set_defaults(func=run)
