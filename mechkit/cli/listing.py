"""`mechkit list`: the registered mechanisms (imports none of them)."""

from __future__ import annotations

import argparse

from mechkit.catalog.registry import ENTRIES
from mechkit.cli.common import examples


def run(args: argparse.Namespace) -> None:
    """Print one line per registered mechanism.

    Args:
        args: the parsed command line (no options).
    """
    for e in ENTRIES:
        print(f"{e.name:<22} {e.summary}")


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `list`.

    Args:
        sub: the command line's sub-parsers.
    """
    sub.add_parser(
        "list", help="registered mechanisms", **examples("mechkit list", "mechkit list | grep planar")
    ).set_defaults(func=run)
