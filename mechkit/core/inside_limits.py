"""An assembly re-sought inside the joints' limits, where Newton from a far start closed the loops outside them.

Newton from a file's own start (its joints' zero, a keyframe) closes the loops on whichever branch it
falls into; a revolute angle then outside its range by more than whole turns (`wrap_into_limits`) means
the file's intended assembly is another one. `seek_inside_limits` looks for it as a bounded least-squares
problem: the closure residual over the free coordinates, each bounded one-coordinate joint (revolute or
prismatic) kept in its [lower, upper] (scipy's trust-region-reflective `least_squares`), stepping on the
configuration manifold from a base configuration (so ball joints take part unbounded; a free body's six
coordinates stay where Newton put them: its pose is not a branch, and a floating crossbar moved to fit the
legs' limits would change what gravity does to it). It starts
from the outside assembly clamped into the limits, then from the limits' midpoints; the exact rows' solve
then polishes the first start that reaches near closure inside the limits.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
from scipy.optimize import least_squares

from mechkit.base.exceptions import ClosureNotConverged
from mechkit.core.assembly import FLIP_TOL, Assembly, _residual_and_jacobian, _solve_rows, flip
from mechkit.core.continuation import LIMIT_TOL, wrap_into_limits
from mechkit.core.model import ClosureData, ClosureModel, InputSplit

#: Residual the bounded search must reach before the exact rows' solve polishes it (m; ours: near enough
#: for Newton's quadratic convergence on a linkage of metre scale).
NEAR_TOL = 1e-6
#: Evaluations of each bounded search (ours: a 36-loop Strandbeest needs a few hundred).
MAX_EVALUATIONS = 400
#: Starts drawn uniformly inside the limits after the clamped and middle ones, and their seed (ours: a
#: Gepetto delta robot's file start needs a few; seeded, so the same file gives the same assembly).
RANDOM_STARTS, SEED = 8, 0


def _bounded(model: pin.Model) -> list[tuple[int, int, float, float]]:
    """(q index, v index, lower, upper) of each one-coordinate joint with a finite range (lower < upper)."""
    out = []
    lo, hi = model.lowerPositionLimit, model.upperPositionLimit
    for j in range(1, model.njoints):
        joint = model.joints[j]
        i = joint.idx_q
        if joint.nq == 1 and joint.nv == 1 and -1e10 < lo[i] < hi[i] < 1e10:
            out.append((i, joint.idx_v, float(lo[i]), float(hi[i])))
    return out


def _starts(model: pin.Model, q: np.ndarray, bounded: list[tuple[int, int, float, float]]) -> list[np.ndarray]:
    """The assembly clamped into the limits, every bounded joint at its range's midpoint, then `RANDOM_STARTS`
    with every bounded joint drawn uniformly in its range (seeded)."""
    rng = np.random.default_rng(SEED)
    starts = [q.copy() for _ in range(2 + RANDOM_STARTS)]
    for i, _, lo, hi in bounded:
        starts[0][i] = min(max(q[i], lo), hi)
        starts[1][i] = 0.5 * (lo + hi)
        for start in starts[2:]:
            start[i] = rng.uniform(lo, hi)
    return starts


def seek_inside_limits(
    cm: ClosureModel, cd: ClosureData, q: np.ndarray, split: InputSplit, *, tol: float
) -> Assembly | None:
    """An assembly with the given joints at q's values and every bounded joint inside its limits, if one is found.

    Args:
        cm: the closure model.
        cd: its data (workspace; left at the solution when one is found).
        q: (nq,) a configuration carrying the given joints' values (e.g. the assembly found outside the limits).
        split: which joints are given (`ClosureModel.split`); their coordinates are not moved, nor a
            free-flyer's.
        tol: closure residual norm to reach (m for position rows).

    Returns:
        The assembly (q (nq,) inside every finite range, within `LIMIT_TOL`; iterations; residual), or None
        where no start leads to one (the caller keeps the assembly it has and names the joints outside).
    """
    model = cm.model
    floating = {
        v for j in range(1, model.njoints) if model.nvs[j] == 6 for v in range(model.idx_vs[j], model.idx_vs[j] + 6)
    }
    free = np.array([v for v in split.free_v if v not in floating], dtype=int)  # a free body's pose stays put
    movable = set(free.tolist())
    bounded = [b for b in _bounded(model) if b[1] in movable]
    column = {int(v): k for k, v in enumerate(free)}
    for start in _starts(model, q, bounded):
        lower, upper = np.full(free.size, -np.inf), np.full(free.size, np.inf)
        for i, v, lo, hi in bounded:  # a one-coordinate joint moves by its velocity coordinate: q_i = start_i + x
            lower[column[v]], upper[column[v]] = lo - start[i], hi - start[i]
        x0 = np.clip(np.zeros(free.size), lower, upper)

        def at(x: np.ndarray, start: np.ndarray = start) -> np.ndarray:
            step = np.zeros(model.nv)
            step[free] = x
            return pin.integrate(model, start, step)

        def residual(x: np.ndarray) -> np.ndarray:
            return _residual_and_jacobian(cm, cd, at(x), False)[0]

        def jacobian(x: np.ndarray, start: np.ndarray = start) -> np.ndarray:
            step = np.zeros(model.nv)
            step[free] = x
            J = _residual_and_jacobian(cm, cd, pin.integrate(model, start, step), True)[1]
            return J @ pin.dIntegrate(model, start, step, pin.ArgumentPosition.ARG1)[:, free]  # tangent at qx -> x

        fit = least_squares(
            residual, x0, jac=jacobian, bounds=(lower, upper), method="trf", max_nfev=MAX_EVALUATIONS, xtol=1e-15
        )
        if not np.isfinite(fit.cost) or np.sqrt(2 * fit.cost) > NEAR_TOL:
            continue
        try:
            polished = _solve_rows(
                cm, cd, at(fit.x), split, tol=tol, max_iter=30, method="newton", jacobian_at_trials=True
            )
        except ClosureNotConverged:
            continue
        if flip(cm, cd.pin) > FLIP_TOL:
            continue
        q_in = wrap_into_limits(model, polished.q)[0]  # given joints outside their limits are the pose given
        if all(lo - LIMIT_TOL <= q_in[i] <= hi + LIMIT_TOL for i, _, lo, hi in bounded):
            pin.forwardKinematics(model, cd.pin, q_in)
            return Assembly(q_in, fit.nfev + polished.iterations, polished.residual)
    return None
