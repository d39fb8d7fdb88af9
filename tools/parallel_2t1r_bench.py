"""Benchmark of the 2T1R's inverse dynamics, one run: microseconds per motion-law sample and ratios.

Methods, each given the motion of the sample (Pinocchio: its own q, v, a; the others: the paper's
analytic state): Pinocchio constrained RNEA with every joint's reaction (`Mechanism.inverse_dynamics`,
without and with the determinacy rank test), SOC (the three SKCs built from the analytic kinematics
and solved by `mechkit.validation.soc`), classic whole-mechanism virtual work (torques only). The
motion itself is timed too: Pinocchio's closure solve + velocity + acceleration projection vs the
analytic state (eqs. (7)-(9), (12), (15)).

Usage: python tools/parallel_2t1r_bench.py [--samples N] [--repeat R]
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import mechkit
from mechkit.mechanisms.parallel_2t1r.compare import pinocchio_inverse_dynamics, pinocchio_motion
from mechkit.mechanisms.parallel_2t1r.joints import joint_positions
from mechkit.mechanisms.parallel_2t1r.motion_law import (
    MOTION_DURATION,
    motion_law,
    motion_law_states,
    state_at,
)
from mechkit.mechanisms.parallel_2t1r.soc import classic_torques, soc_inverse_dynamics


def _per_sample_us(fn, items, repeat: int) -> float:
    """Best of ``repeat`` passes of the mean time per item (microseconds): the least disturbed pass
    on a shared machine."""
    runs = []
    for _ in range(repeat):
        start = time.perf_counter()
        for item in items:
            fn(item)
        runs.append((time.perf_counter() - start) / len(items))
    return 1e6 * min(runs)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=100, help="motion-law samples in (0, 5] s")
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args(argv)
    mech = mechkit.load("parallel_2t1r")
    p = mech.params
    times = np.linspace(MOTION_DURATION / args.samples, MOTION_DURATION, args.samples)
    states = motion_law_states(p, times)
    motions = [pinocchio_motion(mech, *motion_law(t), joint_positions(p, s)) for t, s in zip(times, states)]
    guesses = [(motion_law(t), q) for t, (q, _, _) in zip(times, motions)]

    rows = {
        "Pinocchio constrained RNEA + reactions": _per_sample_us(
            lambda m: pinocchio_inverse_dynamics(mech, *m, determinacy=False), motions, args.repeat),
        "  + determinacy rank test": _per_sample_us(
            lambda m: pinocchio_inverse_dynamics(mech, *m, determinacy=True), motions, args.repeat),
        "SOC (3 SKCs, analytic Jacobians)": _per_sample_us(lambda s: soc_inverse_dynamics(p, s), states, args.repeat),
        "classic virtual work (torques)": _per_sample_us(lambda s: classic_torques(p, s), states, args.repeat),
        "Pinocchio motion (assemble + v + a)": _per_sample_us(
            lambda g: pinocchio_motion(mech, *g[0], g[1]), guesses, args.repeat),
        "analytic motion state (FK + (12) + (15))": _per_sample_us(
            lambda t: state_at(p, *motion_law(t)), times, args.repeat),
    }
    ref = rows["Pinocchio constrained RNEA + reactions"]
    load = os.getloadavg()[0]
    print(f"2T1R inverse dynamics, {args.samples} motion-law samples, best of {args.repeat} passes "
          f"(load average {load:.1f} on {os.cpu_count()} cores)")
    print(f"{'method':44s} {'us/sample':>10s} {'/ Pinocchio RNEA':>17s}")
    for name, us in rows.items():
        print(f"{name:44s} {us:10.1f} {us / ref:17.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
