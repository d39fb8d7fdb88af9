"""`mechkit params`: a mechanism's parameters with their defaults, units, accepted ranges and meaning.

A registered name lists its parameter class (ranges measured by `mechkit.catalog.ranges`); a xacro
file lists its `<xacro:arg>`s and their defaults (no unit or range is declared there); a URDF
(with `<mechkit:loop>`s, an Extended-URDF sidecar or URDF+ constraints), MJCF or SDFormat file is a
fixed description and has none.
"""

from __future__ import annotations

import argparse
from typing import Any

from mechkit.base.json_text import dumps
from mechkit.cli.common import examples

COLUMNS = ("name", "value", "unit", "range", "ours", "doc")


def rows_of(source: str) -> tuple[list[dict[str, Any]], str]:
    """The parameters of a name or a file.

    Args:
        source: a registered name or a description file.

    Returns:
        (one row per parameter with `COLUMNS`, a note on what the rows are).
    """
    from mechkit.catalog.ranges import param_ranges
    from mechkit.catalog.registry import get_spec
    from mechkit.loading import resolve
    from mechkit.sources import xacro_args

    found = resolve(source)
    if isinstance(found, str):
        cls = get_spec(found).params
        ranges = param_ranges(cls)
        rows = [
            {**row, "range": ranges[row["name"]].text() if ranges[row["name"]] else None} for row in cls().describe()
        ]
        return rows, (
            f"range: what {cls.__name__} accepts for one parameter with the others at their defaults "
            "(SI units, rad); '(ours)': a value chosen by mechkit, not in the source."
        )
    if found.suffix == ".xacro":
        rows = [
            {"name": k, "value": v, "unit": "-", "range": None, "ours": False, "doc": "xacro:arg"}
            for k, v in xacro_args(found).items()
        ]
        return (
            rows,
            f"{found.name}: its xacro arguments (set with --set NAME=VALUE); a xacro file declares no units or ranges.",
        )
    return [], f"{found.name}: a fixed description, no parameters."


def run(args: argparse.Namespace) -> None:
    """Print one row per parameter (or the JSON list).

    Args:
        args: the parsed command line.
    """
    rows, note = rows_of(args.name)
    if args.json:
        print(dumps([{k: row[k] for k in COLUMNS} for row in rows], indent=2))
        return
    table = [("name", "default", "unit", "range", "doc")]
    table += [
        (r["name"], str(r["value"]), r["unit"], r["range"] or "-", r["doc"] + (" (ours)" if r["ours"] else ""))
        for r in rows
    ]
    widths = [max(len(row[i]) for row in table) for i in range(4)]
    for row in table if rows else []:
        print("  ".join(cell.ljust(w) for cell, w in zip(row[:4], widths)) + "  " + row[4])
    print(("\n" if rows else "") + note)


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `params`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "params",
        help="a mechanism's parameters: defaults, units, ranges",
        **examples("mechkit params four_bar", "mechkit params ten_bar --json"),
    )
    p.add_argument(
        "name",
        help="mechanism name (see `mechkit list`) or a description file (.xacro; .urdf, Extended "
        "URDF or URDF+; MJCF .xml; SDFormat .sdf)",
    )
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(func=run)
