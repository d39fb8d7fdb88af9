"""Print the speed of the 2T1R motion-law study (`mechkit.bench.motion_speed`): 501 samples of assembly,
velocities, accelerations, efforts and every reaction, against the 50 ms goal.

Usage: python tools/motion_speed.py [--samples N] [--repeats R]
"""

from __future__ import annotations

import argparse

from mechkit.bench.motion_speed import lines, motion_law_speed


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=501)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args(argv)
    print("\n".join(lines(motion_law_speed(args.samples, args.repeats))))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
