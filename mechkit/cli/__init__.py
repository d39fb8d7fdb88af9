"""The `mechkit` command line: one module per command, the only place in mechkit that prints.

A command module exposes `add_parser(sub)`, which adds its sub-parser and sets `func` (args -> None);
registering a command is one line in `COMMANDS`. Command modules import the heavy parts of mechkit
(viz, bench, ...) inside their `run`, so `mechkit list` starts fast and imports no mechanism.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from mechkit.cli import bench, export, listing, motion, params, report, snapshot, sweep, urdf, validate, view
from mechkit.exceptions import MechkitError

COMMANDS = (listing, urdf, report, snapshot, bench, export, params, sweep, motion, validate, view)


def build_parser() -> argparse.ArgumentParser:
    """The parser of every command in `COMMANDS`."""
    parser = argparse.ArgumentParser(prog="mechkit", description="Closed-loop mechanisms on Pinocchio.")
    sub = parser.add_subparsers(dest="command", required=True)
    for command in COMMANDS:
        command.add_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run one command; errors are one line on stderr and exit status 2."""
    args = build_parser().parse_args(argv)
    try:
        with np.errstate(all="raise"):
            args.func(args)
    except MechkitError as err:
        print(f"mechkit: error: {err}", file=sys.stderr)
        return 2
    except FloatingPointError as err:
        print(f"mechkit: error: numerical failure ({err})", file=sys.stderr)
        return 2
    return 0
