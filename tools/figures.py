"""Draw a mechanism's studies: the figures and the numbers its docs page quotes.

Every registered mechanism declares its studies on its spec (`MechanismSpec.studies`: a function
returning data, the numbers as text, the figures drawn from the data). This runs them, prints the
numbers and writes the figures (default folder: docs/figures); a study whose data carries "snapshot"
(mechanism, q (N, nq), name) also gets its motion drawn as one picture, `<name>.png`.

Usage: python tools/figures.py NAME [STUDY ...] [--out DIR]
       python tools/figures.py --list          (every mechanism's studies)
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

import mechkit
from mechkit.base.exceptions import MechkitError
from mechkit.catalog.registry import get_spec, names

FIGURES = Path(__file__).resolve().parent.parent / "docs" / "figures"


def snapshot(mech: mechkit.Mechanism, q: np.ndarray, name: str, folder: Path) -> Path:
    """`folder/<name>.png`: a study's motion q (samples, nq) as one picture (`mechkit.viz.pages.overlay`: the
    last pose solid, four earlier ones faded), rendered by headless Chromium."""
    from mechkit.viz.browser import screenshot
    from mechkit.viz.pages import overlay

    every = max(1, (len(q) - 1) // 4)
    poses = list(q[::every]) + ([q[-1]] if (len(q) - 1) % every else [])
    with tempfile.TemporaryDirectory() as tmp:
        page = Path(tmp) / f"{name}.html"
        overlay(mech, name, ghosts=len(poses) - 1, path=page, poses=poses)
        return screenshot(page, folder / f"{name}.png")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("name", nargs="?", help="a registered mechanism")
    parser.add_argument("studies", nargs="*", help="its studies (default: all)")
    parser.add_argument("--out", type=Path, default=FIGURES, help="folder of the figures")
    parser.add_argument("--list", action="store_true", help="list every mechanism's studies and stop")
    args = parser.parse_args(argv)
    if args.list or args.name is None:
        for name in names():
            for study, declared in get_spec(name).studies.items():
                print(f"{name} {study}: {declared.doc}")
        return 0
    try:
        mech = mechkit.load(args.name)
        declared = mech.spec.studies
        unknown = [s for s in args.studies if s not in declared]
        if unknown:
            print(
                f"{args.name} has the studies: {', '.join(declared) or 'none'} (not {', '.join(unknown)})",
                file=sys.stderr,
            )
            return 2
        for study in args.studies or declared:
            print(f"== {args.name} {study}: {declared[study].doc}")
            with np.errstate(all="ignore"):
                data = declared[study].run(mech)
            print("\n".join(declared[study].lines(data)))
            for path in declared[study].figures(data, args.out) if declared[study].figures else ():
                print(f"wrote {path}")
            if isinstance(data, dict) and "snapshot" in data:
                print(f"wrote {snapshot(*data['snapshot'], args.out)}")
    except MechkitError as err:
        print(f"error: {err}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
