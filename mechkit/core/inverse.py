"""Constrained inverse dynamics (constrained RNEA): actuator efforts and every joint's reaction.

`[S^T, J^T] [u; lambda] = rnea(q, v, a, f_ext) - tau_passive`, S the actuation, J the closure rows.
Every tree joint's transmitted wrench is the RNEA's minus the cut wrenches acting on its subtree
(`ClosureKernel.joint_loads`); a cut joint transmits its cut wrench. Per sample, the work is
Pinocchio's (`computeJointJacobians`, `rnea`) and reading its arrays; the rest is numpy over the
sample axis: the closure kernel, the regularity of the passive block (`mechkit.core.rank`), one
solve (LAPACK gesv where [S^T, J^T] is square, QR where it has full rank, an SVD otherwise), the
reactions, and the determinacy test (`mechkit.core.determinacy`). `inverse_dynamics` is one sample,
`inverse_dynamics_batch` N; they give the same numbers.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pinocchio as pin
import scipy.linalg
import scipy.linalg.lapack

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.core import rank
from mechkit.core.determinacy import determinacy, system
from mechkit.core.kinematics import idle_count
from mechkit.core.model import ClosureData, ClosureModel
from mechkit.core.results import BatchInverseDynamicsResult, InverseDynamicsResult

DISTRIBUTIONS = ("min_norm", "min_effort")


def inverse_pass(cm: ClosureModel, cd: ClosureData, Q: np.ndarray, V: np.ndarray, A: np.ndarray,
                 fexts: Sequence) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per sample, Pinocchio's passes, read: every joint's rotation (N, nj, 3, 3) and origin (N, nj, 3),
    `data.J` (N, 6, nv), rnea torques (N, nv), and the tree joints' wrenches `data.f` in world axes about
    each joint origin (N, nj - 1, 6): the reactions before the cut wrenches act."""
    model, data = cm.model, cd.pin
    n, nj = len(Q), model.njoints
    R = np.empty((n, nj, 3, 3))
    t = np.empty((n, nj, 3))
    J = np.empty((n, 6, model.nv))
    tau = np.empty((n, model.nv))
    f = np.empty((n, nj, 2, 3))
    jacobians, rnea = pin.computeJointJacobians, pin.rnea
    rotations, translations, forces, J_view = cd.rotations, cd.translations, cd.forces, cd.J
    for i in range(n):
        q = Q[i]
        jacobians(model, data, q)
        J[i] = J_view
        R[i] = rotations
        t[i] = translations
        tau[i] = rnea(model, data, q, V[i], A[i]) if fexts[i] is None else rnea(model, data, q, V[i], A[i], fexts[i])
        f[i] = np.reshape(forces, (nj, 2, 3))
    with np.errstate(under="ignore"):
        world = (R[:, 1:, None] @ f[:, 1:, :, :, None]).reshape(n, nj - 1, 6)
    return R, t, J, tau, world


def _used_placements(cm: ClosureModel, R: np.ndarray, t: np.ndarray) -> np.ndarray:
    """(N, n_used, 4, 4) homogeneous placements of the joints carrying cut frames."""
    used = cm.kernel.joints
    G = np.zeros(R.shape[:1] + (used.size, 4, 4))
    G[..., :3, :3], G[..., :3, 3], G[..., 3, 3] = R[:, used], t[:, used], 1.0
    return G


def _check_regular(cm: ClosureModel, Jrows: np.ndarray, Jw: np.ndarray, residuals: np.ndarray,
                   generic_rank: int, idle: bool) -> dict[int, np.ndarray]:
    """Raise `SingularConfiguration` where a sample's passive block (the closure Jacobian on the
    unactuated motions, `ClosureModel.unactuated`) has lost rank, to what the closure residual resolves
    (`rank.passive_verdict` on its first min(generic rank, columns) singular values: an under-actuated
    mechanism's block has more columns than independent rows), idle freedoms (`kinematics.idle_count`)
    aside.

    The resolvable limit grows with s_max and the residual, so the batch's largest of each bounds every
    sample's limit: only samples at or under that bound are judged one by one (none, at regular poses).

    Returns:
        With `idle` (the mechanism has idle freedoms), sample -> (nv, d) basis of the null space of its
        passive block where that whole space is idle (rods spinning about their own axes); else {}.
    """
    basis = cm.unactuated
    columns = min(basis.shape[1], generic_rank)
    found: dict[int, np.ndarray] = {}
    if min(columns, Jrows.shape[1], len(Jrows)) == 0:
        return found
    blocks = Jrows @ basis
    s = rank.singular_values(blocks)
    if s.shape[1] < columns:
        raise rank.singular_error(s[0], columns, float(residuals[0]))
    bound = rank.resolvable_singular_value(float(s[:, 0].max()), float(residuals.max()))
    suspects = range(len(s)) if idle else np.flatnonzero(s[:, columns - 1] <= bound)
    for i in suspects:
        _, bad = rank.passive_verdict(s[i][None], columns, residuals[i][None])
        exact = rank.numerical_rank(s[i])
        if not bad[0] and exact == basis.shape[1]:
            continue
        null = basis @ np.linalg.svd(blocks[i])[2][exact:].T
        count = idle_count(cm, Jw[i], null)
        if bad[0] and (exact >= columns or count < columns - exact):  # not resolvable, and not idle spins
            raise rank.singular_error(s[i], columns, float(residuals[i]))
        if idle and count == null.shape[1]:
            found[int(i)] = null
    return found


def _idle_accelerations(cm: ClosureModel, cd: ClosureData, Q: np.ndarray, A: np.ndarray, b: np.ndarray,
                        idle: dict[int, np.ndarray]) -> np.ndarray:
    """A with each idle freedom's acceleration set by its own dynamics, N^T (M a + nle - tau) = 0.

    No actuator drives an idle freedom and no closure row holds it (J N = 0), so its acceleration is not
    the caller's to choose: a (minimum-norm) kinematic value would ask a ball joint for a torque about the
    rod's axis. The rnea b is affine in a, b(a + N x) = b(a) + M N x.
    """
    A = A.copy()
    for i, N in idle.items():
        M = pin.crba(cm.model, cd.pin, Q[i])
        M = np.triu(M) + np.triu(M, 1).T
        A[i] -= N @ np.linalg.solve(N.T @ M @ N, N.T @ b[i])
    return A


def _solve(cm: ClosureModel, A: np.ndarray, b: np.ndarray, condition: bool, distribution: str):
    """x (N, cols) with A x = b, and the condition numbers (N,) (nan when `condition` is False).

    Square systems: gesv (with `condition`, after singular values that show every sample regular).
    Otherwise, where every sample has full rank and the solution is unique (or minimum-norm is asked
    for), the least-squares / minimum-norm solution by QR; else by SVD, moved to the least efforts
    for "min_effort". Either way the same unique x, and b must be reachable.
    """
    n, nv, cols = A.shape
    square = nv == cols
    cond = np.full(n, np.nan)
    if square and not condition:
        try:
            return _square_solution(A, b), cond
        except SingularConfiguration:
            pass  # rank deficient (idle freedoms): the SVD below
    s = rank.singular_values(A)
    r = rank.ranks(s)
    cond = s[:, 0] / s[np.arange(n), np.maximum(r, 1) - 1]
    full = bool(np.all(r == min(nv, cols)))
    if square and full:
        return _square_solution(A, b), cond
    if full and (distribution == "min_norm" or cols < nv):
        x, outside = _full_rank_solution(A, b)
        _check_reachable(s, outside, b)
        return x, cond
    U, s, Vt = np.linalg.svd(A, full_matrices=True)
    k = s.shape[1]
    keep = np.arange(k)[None, :] < r[:, None]
    proj = np.einsum("nij,ni->nj", U, b)
    _check_reachable(s, rank.outside_range(U, r, b), b)
    coef = np.where(keep, proj[:, :k] / np.where(keep, s, 1.0), 0.0)
    x = np.einsum("nij,ni->nj", Vt[:, :k], coef)
    if distribution == "min_effort":
        na = len(cm.actuated)
        for i in np.flatnonzero(r < cols):
            x[i] = _least_effort(x[i], Vt[i, r[i]:].T, na)
    return x, cond


def _square_solution(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """x (N, n) with A x = b for square A (N, n, n) by gesv; `SingularConfiguration` where one is singular."""
    n, cols = A.shape[0], A.shape[2]
    if n == 1:  # LAPACK gesv directly: a fraction of np.linalg.solve's overhead on small systems
        _, _, x, info = scipy.linalg.lapack.dgesv(A[0], b[0])
        x = x[None] if info == 0 else np.full((1, cols), np.nan)
    else:
        try:
            x = np.linalg.solve(A, b[..., None])[..., 0]
        except np.linalg.LinAlgError:
            x = np.full((n, cols), np.nan)
    if not np.all(np.isfinite(x)):
        raise SingularConfiguration(float("inf"), "[S^T, J^T]: efforts and multipliers undetermined")
    return x


def _full_rank_solution(A: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The unique least-squares (full column rank) or minimum-norm (full row rank) solution x (N, cols)
    of A x = b by QR, and the norm (N,) of the part of b outside the range of A."""
    if A.shape[1] > A.shape[2]:  # A = Q R: x = R^-1 Q^T b
        Q, R = np.linalg.qr(A)
        c = np.einsum("nij,ni->nj", Q, b)
        x = np.linalg.solve(R, c[..., None])[..., 0]
        return x, np.linalg.norm(b - np.einsum("nij,nj->ni", Q, c), axis=1)
    Q, R = np.linalg.qr(A.transpose(0, 2, 1))  # A^T = Q R: x = Q R^-T b, every b reachable
    return (Q @ np.linalg.solve(R.transpose(0, 2, 1), b[..., None]))[..., 0], np.zeros(len(A))


def _check_reachable(s: np.ndarray, outside: np.ndarray, b: np.ndarray) -> None:
    """`SingularConfiguration` where the part of b outside the range of [S^T, J^T] (singular values s) is
    not negligible: the actuators cannot hold the motion."""
    bad = np.flatnonzero(outside > 1e-9 * np.maximum(np.linalg.norm(b, axis=1), 1.0))
    if bad.size:
        i = int(bad[0])
        raise SingularConfiguration(float(s[i, 0] / s[i, -1]) if s[i, -1] > 0 else float("inf"),
                                    f"[S^T, J^T] does not span the required generalised force (sample {i}): the "
                                    "actuators cannot hold this motion")


def _least_effort(x: np.ndarray, N: np.ndarray, na: int) -> np.ndarray:
    """Move x along the null space N to the smallest efforts |u|, then the smallest multipliers."""
    z = -np.linalg.lstsq(N[:na], x[:na], rcond=None)[0]
    x = x + N @ z
    keep = N @ scipy.linalg.null_space(N[:na]) if na else N
    if keep.size:
        x = x - keep @ np.linalg.lstsq(keep[na:], x[na:], rcond=None)[0]
    return x


def inverse_dynamics_batch(cm: ClosureModel, cd: ClosureData, Q: np.ndarray, V: np.ndarray, A: np.ndarray,
                           fexts: Sequence | None = None, passive: np.ndarray | None = None, *,
                           determinacy_test: bool = True, distribution: str = "min_norm",
                           generic_rank: int | None = None, idle: bool = False) -> BatchInverseDynamicsResult:
    """Actuator efforts and every joint's reaction for N motions (q, v, a) that satisfy the closures.

    Args:
        Q: (N, nq) configurations; V, A: (N, nv) velocities and accelerations (J a + gamma = 0).
        fexts: None or N per-sample external forces per joint (`pin.StdVec_Force`, local frames).
        passive: (N, nv) generalised passive forces (springs, dampers; N m or N), or None.
        determinacy_test: flag the components statics leaves undetermined (else the masks are None).
        distribution: where [S^T, J^T] has a null space (redundant actuation or rows), which solution:
            "min_norm" (smallest |[u; lambda]|) or "min_effort" (smallest |u|, then smallest |lambda|).
        generic_rank: the closure's rank at regular configurations (`mobility` at an assembly): refuse
            samples whose passive block has lost rank to what the closure resolves, and give idle freedoms
            the accelerations their own dynamics gives (`_idle_accelerations`); None: neither.
        idle: the mechanism has idle freedoms (`mechkit.core.structure.idle_freedoms` at an assembly).

    Raises:
        SingularConfiguration: a passive block not resolvably regular (with `generic_rank`), or
            [S^T, J^T] cannot give the required generalised force (efforts undetermined).
        InvalidParameters: an unknown distribution.
    """
    if distribution not in DISTRIBUTIONS:
        raise InvalidParameters("distribution", distribution, f"expected one of {DISTRIBUTIONS}")
    n, na = len(Q), len(cm.actuated)
    R, t, J, b, tree = inverse_pass(cm, cd, Q, V, A, [None] * n if fexts is None else fexts)
    if passive is not None:
        b = b - passive
    k = cm.kernel
    with np.errstate(under="ignore"):  # products of tiny lever arms and forces flush to zero harmlessly
        G = _used_placements(cm, R, t)
        e, Jrows, W = k.evaluate(G, J, Q)
        spins = {} if generic_rank is None else _check_regular(cm, Jrows, J, np.linalg.norm(e, axis=-1), generic_rank, idle)
        if spins:
            A = _idle_accelerations(cm, cd, Q, A, b, spins)
            R, t, J, b, tree = inverse_pass(cm, cd, Q, V, A, [None] * n if fexts is None else fexts)
            if passive is not None:
                b = b - passive
        x, cond = _solve(cm, system(cm, Jrows), b, determinacy_test, distribution)
        origins, cut_points = t[:, 1:], k.cut_points(G)
        reactions = np.concatenate([tree, np.zeros((n, k.ncuts, 6))], axis=1)
        reactions += k.joint_loads(W, x[:, na:], origins, cut_points)
        flags = effort_flags = None
        if determinacy_test:
            flags, effort_flags = determinacy(cm, cd, G, J, Q, origins, cut_points)
    return BatchInverseDynamicsResult(cm.joint_names, cm.actuated, x[:, :na], reactions, cm.supports, x[:, na:],
                                      cond, flags, effort_flags)


def inverse_dynamics(cm: ClosureModel, cd: ClosureData, q: np.ndarray, v: np.ndarray, a: np.ndarray,
                     fext: pin.StdVec_Force | None = None, passive: np.ndarray | None = None, *,
                     determinacy_test: bool = True, distribution: str = "min_norm",
                     generic_rank: int | None = None, idle: bool = False) -> InverseDynamicsResult:
    """One sample of `inverse_dynamics_batch`: q (nq,), v and a (nv,), fext per joint or None,
    passive (nv,) or None."""
    out = inverse_dynamics_batch(cm, cd, q[None], v[None], a[None], [fext], None if passive is None else passive[None],
                                 determinacy_test=determinacy_test, distribution=distribution,
                                 generic_rank=generic_rank, idle=idle)
    return out.sample(0)


def multiplier_reactions(cm: ClosureModel, cd: ClosureData, q: np.ndarray, lam: np.ndarray) -> np.ndarray:
    """(n_joints, 6) what closure-row multipliers lam (rows,) alone transmit through every joint at q
    (nq,): the reactions of a self-stress, with no load and no motion (`ClosureModel.joint_names` order;
    [f, m about the joint's point], world)."""
    n, nj = 1, cm.model.njoints
    R, t, _, _, _ = inverse_pass(cm, cd, q[None], np.zeros((n, cm.nv)), np.zeros((n, cm.nv)), [None])
    G = _used_placements(cm, R, t)
    k = cm.kernel
    return k.joint_loads(k.row_wrenches(G), lam[None], t[:, 1:nj], k.cut_points(G))[0]
