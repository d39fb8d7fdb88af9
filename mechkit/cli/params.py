"""`mechkit params`: a mechanism's parameters with their defaults, units, accepted ranges and meaning."""

from __future__ import annotations

import argparse

from mechkit.cli.common import examples


def run(args: argparse.Namespace) -> None:
    """Print one row per parameter (or the JSON list)."""
    import json

    from mechkit.param_ranges import param_ranges
    from mechkit.registry import get_spec

    cls = get_spec(args.name).params
    ranges = param_ranges(cls)
    rows = [{**row, "range": ranges[row["name"]].text() if ranges[row["name"]] else None}
            for row in cls().describe()]
    if args.json:
        print(json.dumps([{k: row[k] for k in ("name", "value", "unit", "range", "ours", "doc")} for row in rows], indent=2))
        return
    table = [("name", "default", "unit", "range", "doc")]
    table += [(r["name"], str(r["value"]), r["unit"], r["range"] or "-", r["doc"] + (" (ours)" if r["ours"] else ""))
              for r in rows]
    widths = [max(len(row[i]) for row in table) for i in range(4)]
    for row in table:
        print("  ".join(cell.ljust(w) for cell, w in zip(row[:4], widths)) + "  " + row[4])
    print(f"\nrange: what {cls.__name__} accepts for one parameter with the others at their defaults "
          "(SI units, rad); '(ours)': a value chosen by mechkit, not in the source.")


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `params`."""
    p = sub.add_parser("params", help="a mechanism's parameters: defaults, units, ranges",
                       **examples("mechkit params four_bar", "mechkit params ten_bar --json"))
    p.add_argument("name", help="mechanism name (see `mechkit list`)")
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(func=run)
