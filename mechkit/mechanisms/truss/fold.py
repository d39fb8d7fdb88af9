"""The paper's 200 s fold on a truss model: closure solved along the drive laws by continuation.

Works on the unit `tetra_3rr3uru` and the composite `deployable_9rr12uru` alike (the units present
are read from the model). `fold_poses` is the "fold" scene of both.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import ClosureNotConverged, InvalidParameters
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.truss.drives import FOLD_DURATION, drive_state
from mechkit.mechanisms.truss.joint_state import drive_inputs


@dataclass(frozen=True)
class FoldSample:
    """One instant of the fold: time (s), q, v, a, and the solver iterations it took."""

    t: float
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    iterations: int


def apexes(mech: Mechanism) -> tuple[str, ...]:
    """Unit apexes present in the model (H for the unit; H, J, I for the composite).

    Args:
        mech: `tetra_3rr3uru` or `deployable_9rr12uru`.

    Returns:
        Apex letters.
    """
    return tuple(a for a in ("H", "J", "I") if mech.model.existJointName(f"A{a}_{a}"))


def fold_step(
    mech: Mechanism, q: np.ndarray, v: np.ndarray, t_prev: float, t: float, tol: float, depth: int = 0
) -> FoldSample:
    """Closure solve at t (s) from the state (q, v) at t_prev (s): predictor q + v dt, then Newton on the
    passive coordinates; the interval is halved (up to 8 times) when Newton does not converge.

    Args:
        mech: `tetra_3rr3uru` or `deployable_9rr12uru`.
        q: (nq,) configuration at t_prev.
        v: (nv,) velocity at t_prev.
        t_prev: the time of the state, s.
        t: the time to solve at, s.
        tol: closure residual to reach (m / dimensionless).
        depth: halvings so far.

    Returns:
        The sample at t: q, v, a and the Newton iterations.

    Raises:
        ClosureNotConverged: still not converged after 8 halvings.
    """
    s = drive_state(t)
    angles, rates, accs = drive_inputs(mech.params, s, mech.actuated, apexes(mech))
    guess = pin.integrate(mech.model, q, v * (t - t_prev))
    for joint, value in angles.items():
        guess[mech.q_index(joint)] = value
    try:
        solved = mech.solve_closure(guess, list(angles), tol=tol)
        q_new, iterations = solved.q, solved.iterations
    except ClosureNotConverged:
        if depth >= 8:
            raise
        half = fold_step(mech, q, v, t_prev, 0.5 * (t_prev + t), tol, depth + 1)
        return fold_step(mech, half.q, half.v, half.t, t, tol, depth + 1)
    v_new = mech.velocities(q_new, rates, list(rates))
    return FoldSample(float(t), q_new, v_new, mech.accelerations(q_new, v_new, accs, list(accs)), iterations)


def fold(mech: Mechanism, times: np.ndarray, tol: float = 1e-12) -> list[FoldSample]:
    """The paper's fold: drive laws alpha(t), gamma(t) on every drive, closure solved at each time.

    Continuation from the reference configuration (t = 0): each solve starts from the previous
    state advanced by v dt (first-order predictor), with interval halving when a step is too long.
    Velocities and accelerations are the closure projections of the drive rates and accelerations.

    Args:
        mech: `tetra_3rr3uru` or `deployable_9rr12uru`.
        times: increasing times in [0, 200] s.
        tol: closure residual to reach (m / dimensionless).

    Returns:
        One sample per time: t, q, v, a, iterations.

    Raises:
        InvalidParameters: times that are not a non-empty, strictly increasing 1-D array in [0, 200] s.
    """
    times = np.asarray(times, dtype=float)
    if times.ndim != 1 or times.size == 0 or np.any(np.diff(times) <= 0):
        raise InvalidParameters("times", times, "must be a non-empty, strictly increasing 1-D array")
    out: list[FoldSample] = []
    state = fold_step(mech, mech.home_q, np.zeros(mech.model.nv), 0.0, 0.0, tol)
    for t in times:
        state = fold_step(mech, state.q, state.v, state.t, float(t), tol)
        out.append(state)
    return out


def fold_times(step: float = 1.0) -> np.ndarray:
    """Sample times of the 200 s fold every `step` s (0 < step <= 200), s.

    Args:
        step: the step, s.

    Returns:
        The times, s, from 0 to 200.

    Raises:
        InvalidParameters: a step outside (0, 200] s.
    """
    if not 0.0 < step <= FOLD_DURATION:
        raise InvalidParameters("step", step, f"must lie in (0, {FOLD_DURATION}] s")
    return np.linspace(0.0, FOLD_DURATION, round(FOLD_DURATION / step) + 1)


def fold_poses(mech: Mechanism) -> list[np.ndarray]:
    """The 200 s fold sampled every 1 s: 201 assembled configurations (the "fold" scene).

    Args:
        mech: `tetra_3rr3uru` or `deployable_9rr12uru`.

    Returns:
        The configurations (nq,).
    """
    return [s.q for s in fold(mech, fold_times(1.0))]


def fold_scene_times(mech: Mechanism, poses: int) -> np.ndarray:
    """Times (s) of the fold scene's poses: uniform over the 200 s fold.

    Args:
        mech: `tetra_3rr3uru` or `deployable_9rr12uru`.
        poses: the number of poses.

    Returns:
        (poses,) times, s.
    """
    return np.linspace(0.0, FOLD_DURATION, poses)
