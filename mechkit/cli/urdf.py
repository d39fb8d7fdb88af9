"""`mechkit urdf`: the URDF generated from the parameters."""

from __future__ import annotations

import argparse

from mechkit.base.atomic import STDOUT, write_text
from mechkit.cli.common import add_mechanism_arguments, examples, load_mechanism


def run(args: argparse.Namespace) -> None:
    """Build the mechanism (which checks that it assembles), then print or write its URDF (`mechkit.export.urdf`:
    the description's own text with its actuators and home declared, or generated from the model).

    Args:
        args: the parsed command line.
    """
    from mechkit.export import to_urdf

    write_text(args.output or STDOUT, to_urdf(load_mechanism(args)))


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `urdf`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "urdf",
        help="print or write the URDF generated from the parameters",
        **examples("mechkit urdf four_bar --set crank=0.12", "mechkit urdf ten_bar -o ten_bar.urdf"),
    )
    add_mechanism_arguments(p)
    p.add_argument("-o", "--output", help="file to write (default or -: standard output)")
    p.set_defaults(func=run)
