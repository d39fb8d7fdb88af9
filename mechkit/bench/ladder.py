"""The ladder of N four-bar loops (`mechkit.bench.ladder_model`): forward dynamics cost and error against N.

For each N: one state (q = 0, input rates ~ N(0, 1), efforts ~ N(0, 0.1) N m, seed 0), the exact
accelerations from the dense KKT on mechkit's independent closure rows, solved by LU with iterative
refinement (residual in extended precision, `exact_accelerations`); then microseconds per call of
the raw `pin.constraintDynamics` (mu = 1e-9, the core's default) and of
`Mechanism.forward_dynamics(method="lcaba")` (`pin.lcaba` at the core's defaults, its closure error
certified), timed alternately repeat after repeat in one process, each keeping its fastest repeat
(the least disturbed on a shared machine), and their ratio; the relative error of each against the
exact accelerations. Growth: the least-squares slope of log t against log N over N >= `FIT_FROM`.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import scipy.linalg

from mechkit import core
from mechkit.bench.ladder_model import ladder
from mechkit.bench.raw import raw_constraint_dynamics
from mechkit.bench.timing import time_per_call
from mechkit.mechanism import Mechanism

SIZES = (1, 2, 4, 8, 16, 32, 64)
FIT_FROM = 4


@dataclass(frozen=True)
class LadderPoint:
    """One ladder size: microseconds per call and relative error (max |a - a_exact| / max |a_exact|)."""

    loops: int
    nv: int
    raw_us: float
    raw_error: float
    lcaba_us: float
    lcaba_error: float
    lcaba_iterations: int
    load: float  # the machine's 1-minute load average after the timing

    @property
    def ratio(self) -> float:
        """lcaba time / raw constraintDynamics time (timed alternately in one process)."""
        return self.lcaba_us / self.raw_us


def exact_accelerations(mech: Mechanism, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """Accelerations of the dense KKT `[M, -J^T; J, 0] [a; lambda] = [tau - nle; -gamma]` on the independent
    rows, LU-solved then refined four times with the residual in extended precision (np.longdouble).

    Args:
        mech: the mechanism.
        q: an assembled configuration (nq,).
        v: a velocity satisfying the closure (nv,).
        tau: generalised efforts (nv,), N m or N.

    Returns:
        The accelerations (nv,), rad/s^2 or m/s^2, exact to rounding.
    """
    J, gamma = mech.closure_jacobian(q), mech.closure_drift(q, v)
    rows = core.independent_rows(J)
    J, gamma = J[rows], gamma[rows]
    data = mech.model.createData()
    M = pin.crba(mech.model, data, q)
    M = np.triu(M) + np.triu(M, 1).T
    nle = pin.nonLinearEffects(mech.model, data, q, v)
    n, k = M.shape[0], rows.size
    K = np.zeros((n + k, n + k))
    K[:n, :n], K[:n, n:], K[n:, :n] = M, -J.T, J
    rhs = np.concatenate([tau - nle, -gamma])
    lu = scipy.linalg.lu_factor(K)
    x = scipy.linalg.lu_solve(lu, rhs)
    K_ext, rhs_ext = K.astype(np.longdouble), rhs.astype(np.longdouble)
    for _ in range(4):
        x = x + scipy.linalg.lu_solve(lu, (rhs_ext - K_ext @ x.astype(np.longdouble)).astype(float))
    return x[:n]


def measure(loops: int, budget: float = 0.2, repeats: int = 5) -> LadderPoint:
    """Time (alternately, fastest of `repeats` each) and error of the raw constraintDynamics and of lcaba
    on the ladder of `loops` loops.

    Args:
        loops: the ladder's number of four-bar loops.
        budget: seconds of timing per repeat.
        repeats: timed repeats of each method.

    Returns:
        The sizes, times (us per call), errors against `exact_accelerations`, lcaba's iterations and the load
            average.
    """
    mech = ladder(loops)
    rng = np.random.default_rng(0)
    q = mech.home_q
    v = mech.velocities(q, rng.normal(size=loops))
    tau = rng.normal(0.0, 0.1, mech.model.nv)
    exact = exact_accelerations(mech, q, v, tau)
    scale = max(float(np.max(np.abs(exact))), 1e-300)
    bare = raw_constraint_dynamics(mech)

    def raw(_):
        return bare(q, v, tau)

    def lcaba(_):
        return mech.forward_dynamics(q, v, tau, "lcaba")

    raw_error = float(np.max(np.abs(raw(None) - exact))) / scale
    result = lcaba(None)
    lcaba_error = float(np.max(np.abs(result.a - exact))) / scale
    iterations = result.iterations
    pairs = [
        (
            time_per_call(raw, [None], budget / repeats / 2, 1)[0],
            time_per_call(lcaba, [None], budget / repeats / 2, 1)[0],
        )
        for _ in range(repeats)
    ]
    return LadderPoint(
        loops,
        mech.model.nv,
        min(p[0] for p in pairs) * 1e6,
        raw_error,
        min(p[1] for p in pairs) * 1e6,
        lcaba_error,
        iterations,
        os.getloadavg()[0],
    )


def growth(points: list[LadderPoint], attr: str) -> float:
    """Least-squares slope p of log t = p log N + c over the points with N >= FIT_FROM.

    Args:
        points: the measured sizes.
        attr: the time to fit ("raw_us" or "lcaba_us").

    Returns:
        The slope p (-), NaN with fewer than two points.
    """
    pts = [(p.loops, getattr(p, attr)) for p in points if p.loops >= FIT_FROM]
    if len(pts) < 2:
        return float("nan")
    n, t = np.log(np.array(pts)).T
    return float(np.polyfit(n, t, 1)[0])


def run(sizes: tuple[int, ...] = SIZES, budget: float = 0.2, repeats: int = 5) -> list[LadderPoint]:
    """`measure` at every ladder size.

    Args:
        sizes: the ladder sizes (loops).
        budget: seconds of timing per repeat.
        repeats: timed repeats of each method.

    Returns:
        One point per size.
    """
    return [measure(n, budget, repeats) for n in sizes]


def markdown(points: list[LadderPoint]) -> list[str]:
    """The benchmark page's ladder section: the table, the growth fits and its targets (lcaba under 1 ms at
    the largest size, growing at most as N^1.3, within 1e-10 of the exact accelerations).

    Args:
        points: the measured sizes.

    Returns:
        Markdown lines.
    """
    lines = [
        (
            "| loops | nv | raw constraintDynamics us | its error | lcaba us | its error | lcaba / raw "
            "| lcaba iterations |"
        ),
        "|---|---|---|---|---|---|---|---|",
    ]
    for p in points:
        lines.append(
            f"| {p.loops} | {p.nv} | {p.raw_us:.1f} | {p.raw_error:.1e} | {p.lcaba_us:.1f} | "
            f"{p.lcaba_error:.1e} | {p.ratio:.2f} | {p.lcaba_iterations} |"
        )
    raw_p, lc_p = growth(points, "raw_us"), growth(points, "lcaba_us")
    loads = [p.load for p in points]
    lines += [
        "",
        (
            f"Growth (slope of log t on log N, N >= {FIT_FROM}): raw constraintDynamics N^{raw_p:.2f}, "
            f"lcaba N^{lc_p:.2f}. Load average (1 min) during the run: {min(loads):.1f} to {max(loads):.1f}."
        ),
    ]
    last = max(points, key=lambda p: p.loops)
    checks = [
        (f"lcaba at {last.loops} loops under 1 ms", last.lcaba_us < 1000.0, f"{last.lcaba_us:.0f} us"),
        ("lcaba growth at most N^1.3", lc_p <= 1.3, f"N^{lc_p:.2f}"),
        (
            "lcaba error at most 1e-10",
            max(p.lcaba_error for p in points) <= 1e-10,
            f"worst {max(p.lcaba_error for p in points):.1e}",
        ),
    ]
    lines += [""] + [f"- {label}: {value}: {'met' if ok else 'MISSED'}" for label, ok, value in checks]
    return lines
