"""What several commands share: the mechanism argument and its parameter overrides."""

from __future__ import annotations

import argparse
from typing import Any

from mechkit.exceptions import MechkitError
from mechkit.mechanism import Mechanism, load


def examples(*commands: str) -> dict[str, Any]:
    """`add_parser` keywords ending a command's `--help` with its examples (one command line each)."""
    return {"epilog": "examples:\n" + "\n".join(f"  {c}" for c in commands),
            "formatter_class": argparse.RawDescriptionHelpFormatter}


def add_mechanism_arguments(parser: argparse.ArgumentParser) -> None:
    """The positional mechanism name and the repeatable `--set NAME=VALUE`."""
    parser.add_argument("name", help="mechanism name (see `mechkit list`)")
    parser.add_argument("--set", action="append", metavar="NAME=VALUE", help="override a parameter (SI units, rad)")


def overrides(pairs: list[str] | None) -> dict[str, str]:
    """`--set` pairs as a dict; a pair without '=' is an error."""
    out = {}
    for pair in pairs or []:
        if "=" not in pair:
            raise MechkitError(f"--set expects name=value, got {pair!r}")
        key, value = pair.split("=", 1)
        out[key.strip()] = value.strip()
    return out


def load_mechanism(args: argparse.Namespace) -> Mechanism:
    """The mechanism the command line names, with its overrides."""
    return load(args.name, **overrides(args.set))
