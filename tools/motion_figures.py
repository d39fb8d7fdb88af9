"""Motion-study figures of the motion laws the mechanisms declare (`MechanismSpec.motion_laws`: the
2T1R's paper law, the ten-bar's deployment at every RK4 step): efforts and the law's chosen reactions
over time, from `mechkit.motion.study` with the determinacy test (the same path as
`mechkit motion ... --plot`), and each peak table printed.

Usage: python tools/motion_figures.py [NAME ...] [--out docs/figures]
Writes OUT/motion_<name>.png (OUT/motion_<name>_<law>.png for a mechanism with several laws).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import mechkit
from mechkit import motion
from mechkit.base.exceptions import MechkitError
from mechkit.catalog.registry import get_spec, names
from mechkit.cli.motion import format_peaks
from mechkit.motion.plot import write_plot

FIGURES = Path(__file__).resolve().parent.parent / "docs" / "figures"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="mechanisms (default: every one that declares a motion law)")
    parser.add_argument("--out", type=Path, default=FIGURES)
    args = parser.parse_args(argv)
    try:
        for name in args.names or [n for n in names() if get_spec(n).motion_laws]:
            mech = mechkit.load(name)
            laws = mech.spec.motion_laws
            for law_name, law in laws.items():
                result = motion.study(mech, motion.from_law(mech, law_name), determinacy=True)
                stem = f"motion_{name}" if len(laws) == 1 else f"motion_{name}_{law_name}"
                print("\n".join([f"{name}: {result.source}, {len(result.t)} samples", *format_peaks(result)]))
                print(f"wrote {write_plot(result, args.out / f'{stem}.png', list(law.reactions) or None)}")
    except MechkitError as err:
        print(f"error: {err}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
