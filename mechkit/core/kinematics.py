"""Closed-loop kinematics: closure residual, Jacobian and drift, velocities, accelerations, mobility, for
one sample or a leading sample axis (functions named `*_batch`); assembly is `mechkit.core.assembly`.

"Inputs" are the joints whose values (and rates) are given; the others are solved for
(`ClosureModel.split`) by the passive solve (`mechkit.core.passive_solve`). Every result is judged by
`mechkit.core.rank`: a passive block that does not resolvably determine the motion raises
`SingularConfiguration` (unless `allow_singular`), and an acceleration drift that leaves the range of
the closure Jacobian (a velocity that is not a motion of the mechanism at second order) raises
`InconsistentMotion` (unless `least_squares`). Idle freedoms (a rod spinning about its own axis between
two ball joints: a velocity that closes every loop and moves no body with mass but one) are given their
minimum-norm value, not refused.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InconsistentMotion
from mechkit.core import rank
from mechkit.core.model import ClosureData, ClosureModel, InputSplit
from mechkit.core.passive_solve import solve_passive
from mechkit.core.results import Mobility


def kinematic_pass(
    cm: ClosureModel, cd: ClosureData, Q: np.ndarray, V: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """One Pinocchio pass per sample (`computeJointJacobians`, or its time variation with V).

    Leaves `cd.pin` at the last sample, frame placements updated.

    Args:
        cm: the closure model.
        cd: its data (workspace).
        Q: (N, nq) configurations.
        V: (N, nv) velocities, or None (no time derivatives).

    Returns:
        The used joints' world placements (N, n_used, 4, 4), the WORLD joint Jacobians `data.J`
        (N, 6, nv) and, with V, their time derivatives `data.dJ` (N, 6, nv), else None.
    """
    model, used = cm.model, cm.kernel.joints
    n = len(Q)
    G = np.empty((n, used.size, 4, 4))
    G[..., 3, :3], G[..., 3, 3] = 0.0, 1.0
    J = np.empty((n, 6, model.nv))
    dJ = None if V is None else np.empty((n, 6, model.nv))
    for i in range(n):
        if V is None:
            pin.computeJointJacobians(model, cd.pin, Q[i])
        else:
            pin.computeJointJacobiansTimeVariation(model, cd.pin, Q[i], V[i])
            dJ[i] = cd.dJ
        J[i] = cd.J
        G[i, :, :3] = cd.oMi[used]
    pin.updateFramePlacements(model, cd.pin)
    return G, J, dJ


def closure_residual(cm: ClosureModel, cd: ClosureData, q: np.ndarray) -> np.ndarray:
    """The residual of every kept row.

    Args:
        cm: the closure model.
        cd: its data (workspace; left at q).
        q: (nq,) configuration.

    Returns:
        (rows,) residuals: m for position rows, dimensionless for alignment rows, rad or m for couplings.
    """
    G, _, _ = kinematic_pass(cm, cd, q[None])
    return cm.kernel.residual(G[0], q)


def closure_jacobian(cm: ClosureModel, cd: ClosureData, q: np.ndarray) -> np.ndarray:
    """The Jacobian of the kept rows.

    Args:
        cm: the closure model.
        cd: its data (workspace; left at q).
        q: (nq,) configuration.

    Returns:
        (rows, nv) the closure Jacobian (de/dt = J v).
    """
    G, J, _ = kinematic_pass(cm, cd, q[None])
    return cm.kernel.evaluate(G[0], J[0], q)[1]


def closure_drift(cm: ClosureModel, cd: ClosureData, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The closure drift gamma(q, v), with d2e/dt2 = J a + gamma.

    Args:
        cm: the closure model.
        cd: its data (workspace; left at q).
        q: (nq,) configuration.
        v: (nv,) velocity.

    Returns:
        (rows,) gamma.
    """
    G, J, dJ = kinematic_pass(cm, cd, q[None], v[None])
    k = cm.kernel
    return k.drift(G[0], k.twists(J[0], v), k.twists(dJ[0], v), q, v)


def mobility(cm: ClosureModel, cd: ClosureData, q: np.ndarray) -> Mobility:
    """Degrees of freedom and redundant constraints from the rank of the closure Jacobian at q.

    Args:
        cm: the closure model.
        cd: its data (workspace; left at q).
        q: (nq,) configuration (assembled).

    Returns:
        The degrees of freedom, rows kept, rank, redundant rows and the Jacobian's singular values.
    """
    J = closure_jacobian(cm, cd, q)
    s = np.linalg.svd(J, compute_uv=False) if J.size else np.zeros(0)
    r = rank.numerical_rank(s)
    return Mobility(cm.nv - r, cm.kernel.size, r, cm.kernel.size - r, s)


def velocities_batch(
    cm: ClosureModel,
    cd: ClosureData,
    Q: np.ndarray,
    split: InputSplit,
    rates: np.ndarray,
    *,
    allow_singular: bool = False,
) -> np.ndarray:
    """Joint velocities with J v = 0 at N configurations, from input rates.

    Args:
        cm: the closure model.
        cd: its data (workspace).
        Q: (N, nq) configurations (assembled).
        split: which joints are given (`ClosureModel.split`).
        rates: (N, k) the given joints' velocities (rad/s or m/s).
        allow_singular: return a solution where the passive block is not resolvably regular (see
            `solve_passive`).

    Returns:
        (N, nv) joint velocities.

    Raises:
        SingularConfiguration: see `solve_passive`.
        InconsistentMotion: see `solve_passive`.
    """
    G, Jw, _ = kinematic_pass(cm, cd, Q)
    e, J, _ = cm.kernel.evaluate(G, Jw, Q)
    return solve_passive(cm, J, Jw, split, rates, None, np.linalg.norm(e, axis=-1), allow_singular=allow_singular)[0]


def velocities(
    cm: ClosureModel,
    cd: ClosureData,
    q: np.ndarray,
    split: InputSplit,
    rates: np.ndarray,
    *,
    allow_singular: bool = False,
) -> np.ndarray:
    """Joint velocities with J v = 0 at one configuration (see `velocities_batch`).

    Args:
        cm: the closure model.
        cd: its data (workspace).
        q: (nq,) configuration (assembled).
        split: which joints are given (`ClosureModel.split`).
        rates: (k,) the given joints' velocities (rad/s or m/s).
        allow_singular: return a solution where the passive block is not resolvably regular.

    Returns:
        (nv,) joint velocities.

    Raises:
        SingularConfiguration: see `solve_passive`.
        InconsistentMotion: see `solve_passive`.
    """
    return velocities_batch(cm, cd, q[None], split, rates[None], allow_singular=allow_singular)[0]


def accelerations_batch(
    cm: ClosureModel,
    cd: ClosureData,
    Q: np.ndarray,
    V: np.ndarray,
    split: InputSplit,
    given: np.ndarray,
    *,
    allow_singular: bool = False,
    least_squares: bool = False,
) -> np.ndarray:
    """Joint accelerations with J a + gamma = 0 at N states, from input accelerations.

    Args:
        cm: the closure model.
        cd: its data (workspace).
        Q: (N, nq) configurations (assembled).
        V: (N, nv) velocities (J v = 0).
        split: which joints are given (`ClosureModel.split`).
        given: (N, k) the given joints' accelerations (rad/s^2 or m/s^2).
        allow_singular: return a solution where the passive block is not resolvably regular (see
            `solve_passive`).
        least_squares: where gamma leaves the range of J (no acceleration satisfies every row), return
            the least-squares accelerations (minimum |J a + gamma|, then minimum norm) instead of raising.

    Returns:
        (N, nv) joint accelerations.

    Raises:
        SingularConfiguration: see `solve_passive`.
        InconsistentMotion: see `solve_passive` (not with `least_squares`).
    """
    G, Jw, dJ = kinematic_pass(cm, cd, Q, V)
    k = cm.kernel
    e, J, _ = k.evaluate(G, Jw, Q)
    gamma = k.drift(G, k.twists(Jw, V), k.twists(dJ, V), Q, V)
    return solve_passive(
        cm,
        J,
        Jw,
        split,
        given,
        gamma,
        np.linalg.norm(e, axis=-1),
        allow_singular=allow_singular,
        least_squares=least_squares,
    )[0]


def accelerations(
    cm: ClosureModel,
    cd: ClosureData,
    q: np.ndarray,
    v: np.ndarray,
    split: InputSplit,
    given: np.ndarray,
    *,
    allow_singular: bool = False,
    least_squares: bool = False,
) -> np.ndarray:
    """Joint accelerations with J a + gamma = 0 at one state (see `accelerations_batch`).

    Args:
        cm: the closure model.
        cd: its data (workspace).
        q: (nq,) configuration (assembled).
        v: (nv,) velocity (J v = 0).
        split: which joints are given (`ClosureModel.split`).
        given: (k,) the given joints' accelerations (rad/s^2 or m/s^2).
        allow_singular: return a solution where the passive block is not resolvably regular.
        least_squares: return the least-squares accelerations where gamma leaves the range of J.

    Returns:
        (nv,) joint accelerations.

    Raises:
        SingularConfiguration: see `solve_passive`.
        InconsistentMotion: see `solve_passive` (not with `least_squares`).
    """
    return accelerations_batch(
        cm, cd, q[None], v[None], split, given[None], allow_singular=allow_singular, least_squares=least_squares
    )[0]


def passive_condition(cm: ClosureModel, cd: ClosureData, q: np.ndarray, split: InputSplit) -> float:
    """Condition number of the passive block (the closure Jacobian on the free coordinates).

    Args:
        cm: the closure model.
        cd: its data (workspace; left at q).
        q: (nq,) configuration.
        split: which joints are given (`ClosureModel.split`).

    Returns:
        s_max / s_min of the passive block (inf: singular to what `rank.CLOSURE_TOL` resolves).
    """
    J = closure_jacobian(cm, cd, q)
    s = rank.singular_values(J[None][..., split.free_v])
    return float(rank.passive_verdict(s, split.free_v.size, np.array([rank.CLOSURE_TOL]))[0][0])


def second_order_inconsistency(cm: ClosureModel, cd: ClosureData, q: np.ndarray, v: np.ndarray) -> float:
    """How far a velocity is from a motion of the mechanism at second order.

    Args:
        cm: the closure model.
        cd: its data (workspace; left at q).
        q: (nq,) configuration.
        v: (nv,) velocity.

    Returns:
        min over a of max |J a + gamma| at (q, v): 0 (to rounding) where v is a motion of the mechanism
        at second order, positive where it moves along a freedom that exists only instantaneously.
    """
    return rank.inconsistency(closure_jacobian(cm, cd, q), closure_drift(cm, cd, q, v))


def second_order_velocity(
    cm: ClosureModel, cd: ClosureData, q: np.ndarray, v: np.ndarray, *, tol: float = 1e-12, max_iter: int = 30
) -> np.ndarray:
    """The velocity near v (nv,) at an assembled q (nq,) along which the motion continues at second order.

    A velocity with J v = 0 is a motion at second order only where gamma(q, v) lies in the range of J:
    y_k . gamma(q, v) = 0 for every left null vector y_k of J (a redundant constraint's self-stress).
    gamma is quadratic in v, so on v = N z (N a basis of the null space of J) each condition is a
    quadratic form Q_k(z) = z^T Q_k z, built by polarisation from `closure_drift`. Starting from the z
    of v's projection, minimum-norm Gauss-Newton steps reach the nearest zero of every Q_k. Where J has
    no left null vector, or every Q_k vanishes (a redundancy that holds at every order), v's projection
    onto the null space of J is returned.

    Args:
        cm: the closure model.
        cd: its data (workspace).
        q: (nq,) assembled configuration.
        v: (nv,) velocity to correct.
        tol: relative tolerance on the quadratic conditions (relative to max |Q_k| |z|^2).
        max_iter: Gauss-Newton iteration cap.

    Returns:
        (nv,) the velocity (J v = 0) along which the motion continues at second order.

    Raises:
        InconsistentMotion: no velocity near v satisfies the conditions (the cones do not meet near it).
    """
    J = closure_jacobian(cm, cd, q)
    U, s, Vt = np.linalg.svd(J, full_matrices=True)
    r = rank.numerical_rank(s)
    N, Y = Vt[r:].T, U[:, r:]
    z = N.T @ v
    if Y.shape[1] == 0 or N.shape[1] == 0:
        return N @ z

    def g(x: np.ndarray) -> np.ndarray:
        return Y.T @ closure_drift(cm, cd, q, N @ x)

    d = N.shape[1]
    eye = np.eye(d)
    diag = [g(eye[i]) for i in range(d)]
    Q = np.zeros((Y.shape[1], d, d))
    for i in range(d):
        Q[:, i, i] = diag[i]
        for j in range(i + 1, d):
            Q[:, i, j] = Q[:, j, i] = 0.5 * (g(eye[i] + eye[j]) - diag[i] - diag[j])
    scale = max(float(np.abs(Q).max()), 1e-300)
    for _ in range(max_iter):
        residual = np.einsum("i,kij,j->k", z, Q, z)
        if np.abs(residual).max() <= tol * scale * max(z @ z, 1e-300):
            return N @ z
        z = z - np.linalg.lstsq(2.0 * (Q @ z), residual, rcond=None)[0]
    raise InconsistentMotion(
        float(np.abs(residual).max()),
        tol * scale * float(z @ z),
        "no velocity near the given one "
        "continues at second order (the second-order cones of the redundant constraints do not "
        "meet near it)",
    )
