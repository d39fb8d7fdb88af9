"""`mechkit report`: structure, mobility and self-checks (text or the JSON contract)."""

from __future__ import annotations

import argparse

from mechkit.base.json_text import dumps
from mechkit.cli.common import add_base_arguments, add_mechanism_arguments, assembly_line, examples, load_mechanism


def run(args: argparse.Namespace) -> None:
    """Print the report.

    Args:
        args: the parsed command line.

    Raises:
        SelfCheckFailed: a self-check above `report.CHECK_LIMIT` (after the report is printed).
    """
    from mechkit.base.exceptions import SelfCheckFailed
    from mechkit.report import CHECK_LIMIT, failing_checks, format_report, report

    mech = load_mechanism(args)
    r = report(mech)
    home = mech.home_assembly
    if args.json:
        print(dumps({**r, "assembly": {"branch": home.branch, "outside": list(home.outside)}}, indent=2))
    else:
        print(f"{assembly_line(home)}\n{format_report(r)}")
    failing = failing_checks(r["checks"])
    if failing:
        raise SelfCheckFailed(r["name"], failing, CHECK_LIMIT)


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `report`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "report",
        help="structure, mobility and self-checks",
        **examples("mechkit report five_bar", "mechkit report four_bar --set coupler=0.3 --json"),
    )
    add_mechanism_arguments(p)
    add_base_arguments(p, motion=False)
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(func=run)
