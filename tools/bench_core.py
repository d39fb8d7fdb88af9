"""Core cost per call and its ratio to the raw Pinocchio calls it is made of (`mechkit.bench.core_cost`).

Prints, in one run: microseconds per call (median of repeats) of assembly, constrained ABA,
constrained RNEA with every reaction (with and without the determinacy test), the raw Pinocchio
calls each is built on, their ratios, and (--profile) a cProfile breakdown of the inverse dynamics.

    python tools/bench_core.py [--budget SECONDS] [--profile] [names...]
"""

from __future__ import annotations

import argparse
import sys

from mechkit.base.exceptions import MechkitError
from mechkit.bench.core_cost import measure, profile


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", default=["four_bar", "five_bar"])
    parser.add_argument("--budget", type=float, default=0.3, help="seconds of timing per row")
    parser.add_argument("--profile", action="store_true", help="also print a cProfile breakdown of inverse_dynamics")
    args = parser.parse_args(argv)
    try:
        for name in args.names:
            print(f"== {name}")
            for label, us, comment in measure(name, args.budget):
                print(f"{label:<68} {us:9.2f} us  {comment}")
            if args.profile:
                for determinacy in (False, True):
                    print(
                        f"-- profile of inverse_dynamics(determinacy={determinacy}), per call (cProfile adds overhead)"
                    )
                    for where, own, cum in profile(name, determinacy):
                        print(f"   {where:<78} own {own:8.2f} us  cum {cum:8.2f} us")
    except MechkitError as err:
        print(f"error: {err}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
