"""`mechkit export`: the mechanism as a file (mechkit's URDF, MJCF, Extended URDF, URDF+)."""

from __future__ import annotations

import argparse

from mechkit.cli.common import add_mechanism_arguments, examples, load_mechanism


def run(args: argparse.Namespace) -> None:
    """Write the export and say where.

    Args:
        args: the parsed command line.
    """
    from mechkit.base.atomic import is_stdout
    from mechkit.export import export_command

    for path in export_command(load_mechanism(args), args.format, args.output):
        if not is_stdout(path):
            print(f"wrote {path}")


def _sidecar(args: argparse.Namespace) -> dict[str, str]:
    """The file the Extended-URDF export writes beside its -o (for the output guard)."""
    from mechkit.export import sidecar_path

    if args.format != "extended-urdf" or not args.output or args.output == "-":
        return {}
    return {"-o's .yaml sidecar": str(sidecar_path(args.output))}


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `export`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "export",
        help="write the mechanism for other tools",
        **examples(
            "mechkit export ten_bar --format mjcf -o ten_bar.xml",
            "mechkit export four_bar --format urdf+ -o four_bar.urdf",
        ),
    )
    add_mechanism_arguments(p)
    p.add_argument(
        "--format",
        required=True,
        choices=["urdf", "mjcf", "extended-urdf", "urdf-plus", "urdf+"],
        help="target format: mechkit's URDF (<mechkit:loop>s), MJCF (MuJoCo), Extended URDF (URDF + YAML "
        "sidecar, Gepetto's), URDF+ (loops and couplings inside the URDF; urdf+ is the same)",
    )
    p.add_argument("-o", "--output", required=True, help="file to write (extended-urdf also writes a .yaml beside it)")
    p.set_defaults(func=run, also_writes=_sidecar)
