"""The assembly branch a reference configuration picks: continuation from it, and revolute values in their limits.

A closed loop assembles in several ways for the same inputs; Newton from a far start may land on any
(and returns revolute angles off by multiples of 2 pi). `continue_from` keeps the reference's branch:
it steps the given joints from the reference's values to the target's in steps of at most `MAX_STEP`
(rad or m, ours: small against a linkage's branch separation) and closes the loops after each step by
the exact rows' solve from the previous solution. `wrap_into_limits` then shifts each bounded
revolute angle by whole turns into its range, and names the joints left outside it.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import ClosureNotConverged
from mechkit.core.assembly import FLIP_TOL, Assembly, _solve_rows, flip
from mechkit.core.model import ClosureData, ClosureModel, InputSplit

#: Largest change of a given coordinate per continuation step (rad or m; ours).
MAX_STEP = 0.05
#: How far past a limit an angle still counts as at it (rad; ours: round-off of a solve).
LIMIT_TOL = 1e-9


def _revolutes(model: pin.Model) -> list[tuple[str, int]]:
    """(name, q index) of the bounded one-coordinate revolute joints (RX, RY, RZ, RevoluteUnaligned)."""
    out = []
    for j in range(1, model.njoints):
        joint = model.joints[j]
        if joint.nq == 1 and joint.shortname().startswith(("JointModelR", "JointModelRevolute")):
            out.append((model.names[j], joint.idx_q))
    return out


def wrap_into_limits(model: pin.Model, q: np.ndarray) -> tuple[np.ndarray, tuple[str, ...]]:
    """q with each bounded revolute angle shifted by whole turns into [lower, upper] where a shift does.

    Args:
        model: the Pinocchio model (its position limits).
        q: (nq,) a configuration.

    Returns:
        The shifted q (nq,) (the same placements), and the joints still outside their range, by name.
    """
    q = q.copy()
    outside = []
    lo, hi = model.lowerPositionLimit, model.upperPositionLimit
    for name, i in _revolutes(model):
        if not (-1e10 < lo[i] and hi[i] < 1e10):  # unbounded (inf or a huge stand-in)
            continue
        if lo[i] - LIMIT_TOL <= q[i] <= hi[i] + LIMIT_TOL:
            continue
        shifted = q[i] - 2 * np.pi * np.ceil((q[i] - hi[i] - LIMIT_TOL) / (2 * np.pi))  # the largest below hi
        if shifted >= lo[i] - LIMIT_TOL:
            q[i] = shifted
        else:
            outside.append(name)
    return q, tuple(outside)


def continue_from(
    cm: ClosureModel, cd: ClosureData, q_ref: np.ndarray, q_target: np.ndarray, split: InputSplit, *, tol: float
) -> Assembly | None:
    """The closed configuration on q_ref's branch with the given joints at q_target's values.

    Args:
        cm: the closure model.
        cd: its data (workspace; left at the solution).
        q_ref: (nq,) a closed reference configuration (the file's home, the previous sample).
        q_target: (nq,) its given joints' coordinates are the target inputs (the rest is ignored).
        split: which joints are given.
        tol: residual norm to reach at each step (m for position rows).

    Returns:
        The assembly (q, total iterations, residual), or None where a step fails to close or flips a
        cut (the branch cannot be followed there).
    """
    model = cm.model
    dq = pin.difference(model, q_ref, q_target)
    given = np.zeros(model.nv)
    given[split.input_v] = dq[split.input_v]
    steps = max(1, int(np.ceil(np.max(np.abs(given), initial=0.0) / MAX_STEP)))
    q, iterations, residual = q_ref.copy(), 0, 0.0
    for k in range(1, steps + 1):
        start = pin.integrate(model, q, given / steps)
        try:
            out = _solve_rows(cm, cd, start, split, tol=tol, max_iter=30, method="newton", jacobian_at_trials=True)
        except (ClosureNotConverged, np.linalg.LinAlgError):
            return None
        if flip(cm, cd.pin) > FLIP_TOL:
            return None
        q, iterations, residual = out.q, iterations + out.iterations, out.residual
    return Assembly(q, iterations, residual)
