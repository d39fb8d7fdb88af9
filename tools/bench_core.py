"""Core cost per call and its ratio to the raw Pinocchio calls it is made of (four_bar, five_bar).

Prints, in one run: microseconds per call (median of repeats) of assembly, constrained ABA,
constrained RNEA with every reaction (with and without the determinacy test), the raw Pinocchio
calls each is built on, their ratios, and (--profile) a cProfile breakdown of the inverse dynamics.

    python tools/bench_core.py [--budget SECONDS] [--profile] [names...]
"""

from __future__ import annotations

import argparse

import numpy as np
import pinocchio as pin

import mechkit
from mechkit.bench.methods import references
from mechkit.bench.raw import raw_constraint_dynamics
from mechkit.bench.sampling import make_samples
from mechkit.bench.timing import time_per_call


def _us(fn, sample, budget: float) -> float:
    return float(np.median(time_per_call(lambda s: fn(), [sample], budget, 9))) * 1e6


def measure(name: str, budget: float) -> list[tuple[str, float, str]]:
    """(label, microseconds, comment) rows for one mechanism."""
    m = mechkit.load(name)
    s = make_samples(m, 1)[0]
    references(m, [s])
    q, v, a, tau = s.q, s.v, s.a, s.tau
    model, data = m.model, m.model.createData()
    raw = raw_constraint_dynamics(m)
    inputs = dict(zip(s.input_names, s.inputs))
    start = m.home_q.copy()
    rows = []

    def row(label, fn, comment=""):
        rows.append((label, _us(fn, s, budget), comment))
        return rows[-1][1]

    t_kin = row("raw: computeJointJacobians + updateFramePlacements", lambda: (pin.computeJointJacobians(model, data, q),
                                                                             pin.updateFramePlacements(model, data)))
    t_cd = row("raw: pin.constraintDynamics (mu=1e-9, 20 it)", lambda: raw(q, v, tau))
    t_rnea = row("raw: pin.rnea", lambda: pin.rnea(model, data, q, v, a))
    t_aba = row("raw: pin.aba (tree, no loop)", lambda: pin.aba(model, data, q, v, tau))
    q0 = start.copy()
    for joint, value in inputs.items():
        q0[m.q_index(joint)] = value
    iters = m.solve_closure(q0, list(inputs)).iterations
    for label, fn, base, comment in [
        ("assemble (closure Newton, from home)", lambda: m.assemble(inputs, guess=start), t_kin,
         f"{iters} iterations; ratio to one kinematics update"),
        ("forward_dynamics proximal (constrained ABA)", lambda: m.forward_dynamics(q, v, tau), t_cd, "ratio to raw constraintDynamics"),
        ("forward_dynamics dense KKT", lambda: m.forward_dynamics(q, v, tau, "kkt"), t_cd, "ratio to raw constraintDynamics"),
        ("inverse_dynamics, determinacy=False", lambda: m.inverse_dynamics(q, v, a, determinacy=False), t_cd,
         "ratio to raw constraintDynamics (goal <= 5)"),
        ("inverse_dynamics, determinacy=True", lambda: m.inverse_dynamics(q, v, a, determinacy=True), t_cd,
         "ratio to raw constraintDynamics (goal <= 5)"),
    ]:
        t = row(label, fn)
        rows[-1] = (label, t, f"x{t / base:.1f} {comment}")
    rows.append(("inverse dynamics floor: 2 rnea + kinematics update", 2 * t_rnea + t_kin, f"x{(2 * t_rnea + t_kin) / t_cd:.1f} of raw constraintDynamics"))
    rows.append(("aba (tree)", t_aba, ""))

    return rows


def profile(name: str, determinacy: bool, calls: int = 300, top: int = 12) -> list[tuple[str, float, float]]:
    """cProfile of `inverse_dynamics`: (function, microseconds per ID call own time, cumulative), top by own time."""
    import cProfile
    import pstats

    m = mechkit.load(name)
    s = make_samples(m, 1)[0]
    prof = cProfile.Profile()
    prof.enable()
    for _ in range(calls):
        m.inverse_dynamics(s.q, s.v, s.a, determinacy=determinacy)
    prof.disable()
    stats = pstats.Stats(prof).stats
    rows = []
    for (file, line, fn), (_, _, tottime, cumtime, _) in stats.items():
        where = f"{fn} ({file.rsplit('/', 1)[-1]}:{line})" if line else fn
        rows.append((where, tottime / calls * 1e6, cumtime / calls * 1e6))
    return sorted(rows, key=lambda r: -r[1])[:top]


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", default=["four_bar", "five_bar"])
    parser.add_argument("--budget", type=float, default=0.3, help="seconds of timing per row")
    parser.add_argument("--profile", action="store_true", help="also print a cProfile breakdown of inverse_dynamics")
    args = parser.parse_args(argv)
    for name in args.names:
        print(f"== {name}")
        for label, us, comment in measure(name, args.budget):
            print(f"{label:<68} {us:9.2f} us  {comment}")
        if args.profile:
            for determinacy in (False, True):
                print(f"-- profile of inverse_dynamics(determinacy={determinacy}), per call (cProfile adds overhead)")
                for where, own, cum in profile(name, determinacy):
                    print(f"   {where:<78} own {own:8.2f} us  cum {cum:8.2f} us")


if __name__ == "__main__":
    main()
