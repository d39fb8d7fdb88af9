"""Core cost per call and its ratio to the raw Pinocchio calls it is made of (`tools/bench_core.py`).

`measure` times, on one bench sample of a registered mechanism: the raw Pinocchio calls (kinematics
update, `pin.constraintDynamics`, `pin.rnea`, `pin.aba`), then assembly, constrained forward dynamics
(proximal and dense KKT) and constrained inverse dynamics (with and without the determinacy test),
each with its ratio to the raw call it is built on. `profile` is a cProfile breakdown of the
inverse dynamics. Nothing here prints.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.bench.methods import references
from mechkit.bench.raw import raw_constraint_dynamics
from mechkit.bench.sampling import make_samples
from mechkit.bench.timing import time_per_call
from mechkit.loading import load


def _us(fn, sample, budget: float) -> float:
    return float(np.median(time_per_call(lambda s: fn(), [sample], budget, 9))) * 1e6


def measure(name: str, budget: float) -> list[tuple[str, float, str]]:
    """The core's calls against the raw Pinocchio calls they wrap, for one mechanism.

    Args:
        name: a registered mechanism.
        budget: seconds of timing per row.

    Returns:
        (label, microseconds per call (median of 9 repeats), comment) rows; a core call's comment carries its
            ratio to the raw call.
    """
    m = load(name)
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

    t_kin = row(
        "raw: computeJointJacobians + updateFramePlacements",
        lambda: (pin.computeJointJacobians(model, data, q), pin.updateFramePlacements(model, data)),
    )
    t_cd = row("raw: pin.constraintDynamics (mu=1e-9, 20 it)", lambda: raw(q, v, tau))
    t_rnea = row("raw: pin.rnea", lambda: pin.rnea(model, data, q, v, a))
    t_aba = row("raw: pin.aba (tree, no loop)", lambda: pin.aba(model, data, q, v, tau))
    q0 = start.copy()
    for joint, value in inputs.items():
        q0[m.q_index(joint)] = value
    iters = m.solve_closure(q0, list(inputs)).iterations
    for label, fn, base, comment in [
        (
            "assemble (closure Newton, from home)",
            lambda: m.assemble(inputs, guess=start),
            t_kin,
            f"{iters} iterations; ratio to one kinematics update",
        ),
        (
            "forward_dynamics proximal (constrained ABA)",
            lambda: m.forward_dynamics(q, v, tau),
            t_cd,
            "ratio to raw constraintDynamics (issue 33: <= 2)",
        ),
        (
            "forward_dynamics dense KKT",
            lambda: m.forward_dynamics(q, v, tau, "kkt"),
            t_cd,
            "ratio to raw constraintDynamics",
        ),
        (
            "inverse_dynamics, determinacy=False",
            lambda: m.inverse_dynamics(q, v, a, determinacy=False),
            t_cd,
            "ratio to raw constraintDynamics (issue 33: <= 8 four-bar, <= 5 2T1R)",
        ),
        (
            "inverse_dynamics, determinacy=True",
            lambda: m.inverse_dynamics(q, v, a, determinacy=True),
            t_cd,
            "ratio to raw constraintDynamics (issue 33: <= 1.5x the call without the test)",
        ),
    ]:
        t = row(label, fn)
        rows[-1] = (label, t, f"x{t / base:.1f} {comment}")
    rows.append(
        (
            "inverse dynamics floor: 2 rnea + kinematics update",
            2 * t_rnea + t_kin,
            f"x{(2 * t_rnea + t_kin) / t_cd:.1f} of raw constraintDynamics",
        )
    )
    rows.append(("aba (tree)", t_aba, ""))

    return rows


def profile(name: str, determinacy: bool, calls: int = 300, top: int = 12) -> list[tuple[str, float, float]]:
    """cProfile of `inverse_dynamics`, the functions taking the most time of their own first.

    Args:
        name: a registered mechanism.
        determinacy: with the determinacy test.
        calls: inverse-dynamics calls profiled.
        top: rows returned.

    Returns:
        (function, microseconds per inverse-dynamics call of its own time, cumulative microseconds) rows, `top` of
            them.
    """
    import cProfile
    import pstats

    m = load(name)
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
