"""Motion-study figures of the 2T1R and the ten-bar: efforts and chosen reactions over time, drawn from
`mechkit.motion.study` (the same path as `mechkit motion ... --plot`).

- 2T1R: the paper's motion law, t in (0, 5] s in 501 uniform steps (t = 0 is a parallel singularity);
  reactions of the platform joints R13, R23, R43.
- ten-bar: the deployment scene at every RK4 step (dt = 0.02 s, 1001 poses over 20 s); efforts at the
  motors R1, R3 and at the spring hinge R5; reactions of the wall hinges R1, R5 and of R3.

Usage: python tools/motion_figures.py [--out docs/figures]
Writes OUT/motion_parallel_2t1r.png and OUT/motion_ten_bar.png, and prints each peak table.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import mechkit
from mechkit import motion
from mechkit.cli.motion import format_peaks
from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_DURATION, motion_law
from mechkit.mechanisms.ten_bar.scenes import DEPLOY_STEP, deployment_poses, deployment_times
from mechkit.motion.plot import write_plot

FIGURES = Path(__file__).resolve().parent.parent / "docs" / "figures"


def two_t1r(samples: int = 501) -> motion.MotionResult:
    mech = mechkit.load("parallel_2t1r")
    t = np.linspace(MOTION_DURATION / samples, MOTION_DURATION, samples)
    law = motion.from_callable(mech, motion_law, t, source="motion law theta = pi t (1/18, 1/15, 1/10)")
    return motion.study(mech, law, determinacy=True)


def ten_bar() -> motion.MotionResult:
    mech = mechkit.load("ten_bar")
    frames = round(mech.params.deploy_time / DEPLOY_STEP) + 1
    poses = np.array(deployment_poses(mech, frames))
    names = motion.default_inputs(mech)
    values = poses[:, [mech.q_index(n) for n in names]]
    law = motion.from_arrays(mech, deployment_times(mech, frames), values, names=names, guesses=poses,
                             source="deployment, every RK4 step")
    return motion.study(mech, law, determinacy=True)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=FIGURES)
    args = parser.parse_args(argv)
    for name, result, joints in (("parallel_2t1r", two_t1r(), ["R13", "R23", "R43"]),
                                 ("ten_bar", ten_bar(), ["R1", "R5", "R3"])):
        print("\n".join([f"{name}: {result.source}, {len(result.t)} samples", *format_peaks(result)]))
        print(f"wrote {write_plot(result, args.out / f'motion_{name}.png', joints)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
