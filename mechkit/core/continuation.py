"""The assembly branch a reference configuration picks: continuation from it, and revolute values in their limits.

A closed loop assembles in several ways for the same inputs; Newton from a far start may land on any
(and returns revolute angles off by multiples of 2 pi). `continue_from` keeps the reference's branch:
it steps the given joints from the reference's values to the target's in steps of at most `MAX_STEP`
(rad or m, ours: small against a linkage's branch separation) and closes the loops after each step by
the exact rows' solve from the previous solution; a step that does not close (or flips a cut) is
halved, down to `MAX_STEP` / 2^`HALVINGS` (a deployable's fold needs steps of 2e-3 rad; below that
the branch counts as lost, e.g. at the end of an input's reach), and the step doubles again, up to
`MAX_STEP`, after each success. `wrap_into_limits` then shifts each bounded
revolute angle by whole turns into its range, and names the joints left outside it; `refuse_outside`
refuses such an assembly by the first of them (its value and limits).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import ClosureNotConverged, OutsideLimits
from mechkit.core.assembly import FLIP_TOL, Assembly, _solve_rows, flip
from mechkit.core.model import ClosureData, ClosureModel, InputSplit

#: Largest change of a given coordinate per continuation step (rad or m; ours).
MAX_STEP = 0.05
#: Halvings of the largest step before the branch counts as lost (ours: 0.05 / 2^8 = 2e-4 rad or m).
HALVINGS = 8
#: Longest continuation followed, in steps of `MAX_STEP` (ours: 100 rad or m; farther, the caller's Newton
#: from its guess decides: a target 1e300 rad away once looped for ever).
MAX_STEPS = 2000
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
    """q with each bounded revolute angle shifted by whole turns into [lower, upper] where a shift does
    (a range of zero width, lower = upper, is a URDF's unset limit: no bound, as in Gepetto's files).

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
        if not (-1e10 < lo[i] < hi[i] < 1e10):  # unbounded (inf, a huge stand-in, or lower = upper: unset)
            continue
        if lo[i] - LIMIT_TOL <= q[i] <= hi[i] + LIMIT_TOL:
            continue
        shifted = q[i] - 2 * np.pi * np.ceil((q[i] - hi[i] - LIMIT_TOL) / (2 * np.pi))  # the largest below hi
        if shifted >= lo[i] - LIMIT_TOL:
            q[i] = shifted
        else:
            outside.append(name)
    return q, tuple(outside)


def refuse_outside(model: pin.Model, assembly: Assembly, what: str) -> None:
    """Refuse an assembly that leaves a joint's limits, by the first joint named in `assembly.outside`.

    Args:
        model: the Pinocchio model (its limits).
        assembly: the assembly (its q and the joints `wrap_into_limits` left outside).
        what: which assembly, for the message (e.g. "the home assembly").

    Raises:
        OutsideLimits: a joint outside its limits (name, value, limits, and the branch taken).
    """
    if assembly.outside:
        joint = assembly.outside[0]
        j = model.getJointId(joint)
        i = model.joints[j].idx_q
        lo, hi = float(model.lowerPositionLimit[i]), float(model.upperPositionLimit[i])
        raise OutsideLimits(joint, float(assembly.q[i]), lo, hi, f"{what} ({assembly.branch})")


def continue_from(
    cm: ClosureModel,
    cd: ClosureData,
    q_ref: np.ndarray,
    q_target: np.ndarray,
    split: InputSplit,
    *,
    tol: float,
    start: np.ndarray | None = None,
) -> Assembly | None:
    """The closed configuration on q_ref's branch with the given joints at q_target's values.

    Args:
        cm: the closure model.
        cd: its data (workspace; left at the solution).
        q_ref: (nq,) a closed reference configuration (the file's home, the previous sample).
        q_target: (nq,) its given joints' coordinates are the target inputs (the rest is ignored).
        split: which joints are given.
        tol: residual norm to reach at each step (m for position rows).
        start: (nq,) where one step suffices, the solve's start instead of q_ref with the inputs moved
            (a motion's extrapolation of its last samples; its given coordinates are replaced).

    Returns:
        The assembly (q, total iterations, residual), its revolute angles continuous from q_ref's (each
        step's shifted by whole turns to the nearest of the previous), or None where a step fails to close
        or flips a cut (the branch cannot be followed there) or the inputs move farther than
        `MAX_STEPS` steps.
    """
    model = cm.model
    dq = pin.difference(model, q_ref, q_target)
    given = np.zeros(model.nv)
    given[split.input_v] = dq[split.input_v]
    change = float(np.max(np.abs(given), initial=0.0))
    if not change <= MAX_STEPS * MAX_STEP:  # too far (or not a number): not followed
        return None
    largest = min(1.0, MAX_STEP / max(change, 1e-300))  # of the whole change
    done, step = 0.0, largest
    q, iterations, residual = q_ref.copy(), 0, 0.0
    angles = np.array([i for _, i in _revolutes(model)], dtype=int)
    while done < 1.0:
        step = min(step, 1.0 - done)
        if start is not None and step == 1.0:  # the warm start, its given coordinates at the target's
            moved = np.zeros(model.nv)
            moved[split.input_v] = pin.difference(model, start, q_target)[split.input_v]
            first = pin.integrate(model, start, moved)
        else:
            first = pin.integrate(model, q, given * step)
        try:
            out = _solve_rows(cm, cd, first, split, tol=tol, max_iter=30, method="newton", jacobian_at_trials=True)
        except (ClosureNotConverged, np.linalg.LinAlgError):
            out = None
        if out is None or flip(cm, cd.pin) > FLIP_TOL:
            step /= 2
            if step < largest / 2**HALVINGS:
                return None
            continue
        near = out.q.copy()  # each revolute angle the whole turns nearest the previous step's (same placement)
        near[angles] -= 2 * np.pi * np.round((near[angles] - q[angles]) / (2 * np.pi))
        q, iterations, residual = near, iterations + out.iterations, out.residual
        done = 1.0 if step == 1.0 - done else done + step
        step = min(2 * step, largest)
    return Assembly(q, iterations, residual, "continued from the reference")
