"""Constrained inverse dynamics (constrained RNEA) of closed-loop mechanisms, for N samples at once.

`[S, J^T] [u; lambda] = rnea(q, v, a) - J_ext^T f_ext`, S selecting the actuated joints, J the closure
Jacobian. Every tree joint's transmitted wrench is the RNEA's minus the cut wrenches acting on its
subtree; the cut joints transmit the cut wrenches. The per-sample work is Pinocchio's
(`computeJointJacobians`, `rnea`) and reading its arrays; everything else is one numpy operation
over the sample axis: closure rows as world wrenches and residuals (`mechkit.core.row_wrenches`), the
regularity of the passive block judged on that Jacobian (`_check_regular`), one batched solve
(LAPACK gesv where [S, J^T] is square, QR where it has full rank, an SVD otherwise), the reactions
as batched products, and the determinacy test on self-stress spaces from one QR (`_self_stresses`).
One sample is the batch of one, so the single-sample and batched results are the same numbers.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pinocchio as pin
import scipy.linalg
import scipy.linalg.lapack

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.base.spatial import cross_batch
from mechkit.core.batch import BatchInverseDynamicsResult
from mechkit.core.closures import ClosureRows
from mechkit.core.dynamics import InverseDynamicsResult, subtree_incidence
from mechkit.core.kinematics import RANK_TOL, judge_passive, resolvable_singular_value
from mechkit.core.row_wrenches import RowWrenches

#: Relative threshold under which a reaction component's null-space variation counts as zero.
DETERMINACY_TOL = 1e-8
DISTRIBUTIONS = ("min_norm", "min_effort")
#: Entries of [S, J_full^T] up to which one sample's self-stresses come from one SVD: there it costs less
#: than the QR and its bounds (measured: four-bar, 18 entries, 8 vs 27 us; deployable, 4422, 420 vs 170 us).
SMALL_SYSTEM = 1000


class InverseDynamicsProblem:
    """What constrained RNEA needs besides (q, v, a): built once per mechanism.

    Attributes:
        model, data: the Pinocchio model and a scratch data.
        rows: the closure rows the scene solves with; full_rows: the closures' full spatial rows
            (the physical joints), for the determinacy test (same cuts, same order).
        actuated_v: velocity indices of the actuated joints, in effort order; actuated_names: their names.
        passive_v: the other velocity indices (the passive block's columns).
        joint_names: tree joints (model order) then cut joints; supports: True for joints to the ground.
        stress_rows: rows of [S, J_full^T] independent at the first sample the determinacy test saw.
    """

    def __init__(self, model: pin.Model, data: pin.Data, rows: ClosureRows, full_rows: ClosureRows,
                 actuated_v: np.ndarray, actuated_names: tuple[str, ...]):
        self.model, self.data, self.rows, self.full_rows = model, data, rows, full_rows
        self.actuated_v, self.actuated_names = np.asarray(actuated_v, dtype=int), tuple(actuated_names)
        self.passive_v = np.setdiff1d(np.arange(model.nv), self.actuated_v)
        self._effort_columns = np.arange(self.actuated_v.size)
        self.kept, self.full = RowWrenches(rows), RowWrenches(full_rows)
        # cut wrenches -> what they put on every joint (tree joints but the universe, then the cuts)
        self.load_map = np.vstack([-subtree_incidence(model, rows)[1:], np.eye(len(rows.cuts))])
        cut_names = tuple(c.closure.name for c in rows.cuts)
        self.joint_names = tuple(model.names[1:]) + cut_names
        parents = model.parents
        self.stress_rows: np.ndarray | None = None  # see `_self_stresses`, set on its first call
        # views of data.oMi's rotations and translations, data.f and data.J (they alias data's memory,
        # which lives on self; SE3.np is a copy)
        self._R_views, self._t_views = [M.rotation for M in data.oMi.tolist()], [M.translation for M in data.oMi.tolist()]
        self._f_views, self._J_view = [F.np for F in data.f.tolist()], data.J
        self.supports = np.array([parents[i] == 0 for i in range(1, model.njoints)] + [
            model.frames[c.frame_a].parentJoint == 0 or model.frames[c.frame_b].parentJoint == 0 for c in rows.cuts],
            dtype=bool)


def _gather(p: InverseDynamicsProblem, Q, V, A, fexts) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per sample, Pinocchio's joint placements (N, nj, 4, 4), data.J (N, 6, nv), rnea torques (N, nv)
    and the tree joints' wrenches data.f in world axes about each joint origin, then zeros for the
    cuts (N, nj - 1 + ncuts, 6): the reactions before the cut wrenches act."""
    model, data = p.model, p.data
    n = len(Q)
    oMi = np.zeros((n, model.njoints, 4, 4))
    oMi[:, :, 3, 3] = 1.0
    rotations, translations = oMi[:, :, :3, :3], oMi[:, :, :3, 3]
    J = np.empty((n, 6, model.nv))
    tau = np.empty((n, model.nv))
    f = np.empty((n, model.njoints, 6))
    jacobians, rnea = pin.computeJointJacobians, pin.rnea
    R_views, t_views, f_views, J_view = p._R_views, p._t_views, p._f_views, p._J_view
    for i in range(n):
        q = Q[i]
        jacobians(model, data, q)
        J[i] = J_view
        rotations[i] = R_views
        translations[i] = t_views
        tau[i] = rnea(model, data, q, V[i], A[i]) if fexts[i] is None else rnea(model, data, q, V[i], A[i], fexts[i])
        f[i] = f_views
    R = oMi[:, 1:, None, :3, :3]
    world = np.zeros((n, len(p.load_map), 6))
    with np.errstate(under="ignore"):
        world[:, :model.njoints - 1] = (R @ f[:, 1:].reshape(n, model.njoints - 1, 2, 3, 1)).reshape(n, model.njoints - 1, 6)
    return oMi, J, tau, world


def _cut_loads(p: InverseDynamicsProblem, rw: RowWrenches, W: np.ndarray, lam: np.ndarray, points: np.ndarray) -> np.ndarray:
    """What row multipliers lam (N, K, rows) put on the joints, per set k (N, K, nj - 1 + ncuts, 6): minus
    the tree joints' share of the cut wrenches, then the cut wrenches, each about its joint's point.

    W: (N, rows, 6) row wrenches; points: (N, nj - 1 + ncuts, 3) tree joint origins, then the cuts' p_b.
    """
    loads = p.load_map @ rw.cut_wrenches(W[:, None], lam)  # about the world origin
    loads[..., 3:] -= cross_batch(points[:, None], loads[..., :3])
    return loads


def _system(p: InverseDynamicsProblem, Jrows: np.ndarray) -> np.ndarray:
    """(N, nv, na + rows) matrices [S, J^T]."""
    na = p.actuated_v.size
    A = np.zeros((Jrows.shape[0], p.model.nv, na + Jrows.shape[1]))
    A[:, p.actuated_v, p._effort_columns] = 1.0
    A[:, :, na:] = Jrows.transpose(0, 2, 1)
    return A


def _check_regular(p: InverseDynamicsProblem, Jrows: np.ndarray, residuals: np.ndarray, independent_rows: int) -> None:
    """`kinematics.check_regular` on gathered arrays: raise `SingularConfiguration` where a sample's
    passive block Jrows[:, :, passive_v] is not resolvably regular at its closure residual norm
    `residuals` (N,) (`judge_passive`, whose test this is).

    The resolvable limit grows with s_max and the residual, so the batch's largest of each bounds every
    sample's limit: only samples at or under that bound are judged one by one (none, at regular poses).
    """
    if min(independent_rows, p.passive_v.size, Jrows.shape[1], len(Jrows)) == 0:
        return
    s = _singular_values(Jrows[:, :, p.passive_v])
    k = min(independent_rows, s.shape[1])
    bound = resolvable_singular_value(float(s[:, 0].max()), float(residuals.max()))
    for i in np.flatnonzero(s[:, k - 1] <= bound):
        judge_passive(s[i], independent_rows, float(residuals[i]))


def _singular_values(A: np.ndarray) -> np.ndarray:
    """(N, k) descending singular values of A (N, m, n); one sample through LAPACK directly (a fraction
    of np.linalg.svd's overhead on one small matrix)."""
    if len(A) == 1:
        return scipy.linalg.lapack.dgesdd(A[0], compute_uv=0)[1][None]
    return np.linalg.svd(A, compute_uv=False)


def _ranks(s: np.ndarray) -> np.ndarray:
    """(N,) numerical ranks from descending singular values (N, k), relative to the largest."""
    return np.sum(s > RANK_TOL * np.maximum(s[:, :1], 1e-300), axis=1)


def _solve(p: InverseDynamicsProblem, A: np.ndarray, b: np.ndarray, condition: bool, distribution: str):
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
        return _square_solution(A, b), cond
    s = _singular_values(A)
    r = _ranks(s)
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
    _check_reachable(s, np.linalg.norm(np.where(np.arange(nv)[None, :] >= r[:, None], proj, 0.0), axis=1), b)
    coef = np.where(keep, proj[:, :k] / np.where(keep, s, 1.0), 0.0)
    x = np.einsum("nij,ni->nj", Vt[:, :k], coef)
    if distribution == "min_effort":
        na = p.actuated_v.size
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
        raise SingularConfiguration(float("inf"), "[S, J^T]: efforts and multipliers undetermined")
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
    """`SingularConfiguration` where the part of b outside the range of [S, J^T] (singular values s) is not
    negligible: the actuators cannot hold the motion."""
    bad = np.flatnonzero(outside > 1e-9 * np.maximum(np.linalg.norm(b, axis=1), 1.0))
    if bad.size:
        i = int(bad[0])
        raise SingularConfiguration(float(s[i, 0] / s[i, -1]) if s[i, -1] > 0 else float("inf"),
                                    f"[S, J^T] does not span the required generalised force (sample {i}): the "
                                    "actuators cannot hold this motion")


def _least_effort(x: np.ndarray, N: np.ndarray, na: int) -> np.ndarray:
    """Move x along the null space N to the smallest efforts |u|, then the smallest multipliers."""
    z = -np.linalg.lstsq(N[:na], x[:na], rcond=None)[0]
    x = x + N @ z
    keep = N @ scipy.linalg.null_space(N[:na]) if na else N
    if keep.size:
        x = x - keep @ np.linalg.lstsq(keep[na:], x[na:], rcond=None)[0]
    return x


def _svd_null_spaces(A: np.ndarray) -> np.ndarray:
    """(N, cols, K) right singular vectors of A (N, nv, cols) past each sample's numerical rank (`_ranks`),
    zero columns where a sample's null space is smaller than the largest."""
    if len(A) == 1:  # LAPACK directly, as in `_singular_values`
        _, s, Vt, _ = scipy.linalg.lapack.dgesdd(A[0], full_matrices=1)
        return Vt[int(_ranks(s[None])[0]):].T[None]
    _, s, Vt = np.linalg.svd(A, full_matrices=True)
    r = _ranks(s)
    k, first = Vt.shape[1], int(r.min())
    return np.where((np.arange(first, k)[None, :] >= r[:, None])[..., None], Vt[:, first:], 0.0).transpose(0, 2, 1)


def _self_stresses(p: InverseDynamicsProblem, A: np.ndarray) -> np.ndarray:
    """(N, cols, K) orthonormal bases of the null spaces of A = [S, J_full^T] (N, nv, cols), zero-padded:
    the space `_svd_null_spaces` gives, mostly without an SVD.

    Rows R0 of A, independent at the first sample seen (cached on the problem), give by one QR,
    A[R0]^T = Q R, the null space Q[:, r0:] of A[R0]. It is A's null space exactly when a sample
    passes two bounds, which also make the SVD's rank decision r0: sigma_r0(A) >= sigma_min(R) >=
    1 / |R^-1|_F > RANK_TOL |A|_F >= RANK_TOL sigma_1(A) (rank at least r0) and, N = Q[:, r0:] being
    orthonormal, sigma_(r0+1)(A) <= |A N|_F <= RANK_TOL |A|_F / sqrt(nv) <= RANK_TOL sigma_1(A) (at
    most r0). A sample that fails either (a special configuration) gets the SVD, and so does a single
    small sample (`SMALL_SYSTEM`). Either basis spans the same space, and `_determinacy` depends only
    on that space.
    """
    n, nv, cols = A.shape
    if n == 0:
        return np.zeros((0, cols, 0))
    if n == 1 and nv * cols <= SMALL_SYSTEM:
        return _svd_null_spaces(A)
    if p.stress_rows is None:
        A0 = A[0]
        rank = int(_ranks(np.linalg.svd(A0, compute_uv=False)[None])[0])
        p.stress_rows = np.sort(scipy.linalg.qr(A0.T, mode="r", pivoting=True)[1][:rank])
    r0 = p.stress_rows.size
    if r0 == 0 or r0 == cols:
        return _svd_null_spaces(A)
    Q, R = np.linalg.qr(A[:, p.stress_rows].transpose(0, 2, 1), mode="complete")
    null = Q[:, :, r0:]
    size = np.sqrt(np.einsum("nij,nij->n", A, A))
    try:
        inverse_size = np.sqrt(np.square(np.linalg.inv(R[:, :r0])).sum(axis=(1, 2)))
        ok = (inverse_size * size < 1.0 / RANK_TOL) & (
            np.sqrt(np.square(A @ null).sum(axis=(1, 2))) <= RANK_TOL * size / np.sqrt(nv))
    except np.linalg.LinAlgError:
        ok = np.zeros(n, dtype=bool)
    if ok.all():
        return null
    fallback = _svd_null_spaces(A[~ok])
    out = np.zeros((n, cols, max(cols - r0, fallback.shape[2])))
    out[ok, :, :cols - r0] = null[ok]
    out[~ok, :, :fallback.shape[2]] = fallback
    return out


def _determinacy(p: InverseDynamicsProblem, oMi: np.ndarray, J: np.ndarray, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Which reaction components (N, joints, 6) and efforts (N, na) static equilibrium fixes.

    Tested on the full spatial rows: a component is determinate when it does not change along the
    null space of [S, J_full^T] (Wojtyra and Fraczek 2013); such a null vector is a self-stress (cut
    forces, and actuator efforts, in equilibrium with no load). A component's variation is the norm
    of its changes along an orthonormal basis of that space (`_self_stresses`), the same for every
    such basis; determinate: at most `DETERMINACY_TOL` times the largest. points: as in `_cut_loads`.
    """
    na = p.actuated_v.size
    Wf = p.full.wrenches(oMi)
    null = _self_stresses(p, _system(p, p.full.jacobian(Wf, J)))
    variation = np.sqrt(np.square(_cut_loads(p, p.full, Wf, null[:, na:].transpose(0, 2, 1), points)).sum(axis=1))
    effort_variation = np.sqrt(np.square(null[:, :na]).sum(axis=2))
    scale = np.maximum(np.maximum(variation.max(axis=(1, 2)), effort_variation.max(axis=1, initial=0.0)), 1e-300)
    tol = DETERMINACY_TOL * scale
    return variation <= tol[:, None, None], effort_variation <= tol[:, None]


def inverse_dynamics_batch(p: InverseDynamicsProblem, Q: np.ndarray, V: np.ndarray, A: np.ndarray,
                           fexts: Sequence[pin.StdVec_Force | list[pin.Force] | None] | None = None,
                           determinacy: bool = True, distribution: str = "min_norm",
                           independent_rows: int | None = None) -> BatchInverseDynamicsResult:
    """Actuator efforts and every joint's reaction for N motions (q, v, a) that satisfy the closures.

    Args:
        p: the problem (model, rows, actuators).
        Q: (N, nq) configurations.
        V: (N, nv) velocities.
        A: (N, nv) accelerations satisfying the closures (J a + gamma = 0).
        fexts: None or N per-sample external forces per joint (Pinocchio local frames), e.g. thrust.
        determinacy: run the rank test that flags indeterminate components (an SVD of the full
            spatial rows per sample); without it the masks are None (not tested).
        distribution: where [S, J^T] has a null space (redundant actuation or rows), which solution:
            "min_norm" (smallest `|[u; lambda]|`) or "min_effort" (smallest |u|, then smallest |lambda|).
        independent_rows: the closure's generic rank: check every sample's passive block first
            (`kinematics.check_regular` on the gathered arrays); None: no check.

    Raises:
        SingularConfiguration: a passive block not resolvably regular (with `independent_rows`), or
            [S, J^T] has lost rank where it must not (efforts undetermined).
        InvalidParameters: an unknown distribution.
    """
    if distribution not in DISTRIBUTIONS:
        raise InvalidParameters("distribution", distribution, f"expected one of {DISTRIBUTIONS}")
    n, na = len(Q), p.actuated_v.size
    oMi, J, b, tree_world = _gather(p, Q, V, A, [None] * n if fexts is None else fexts)
    with np.errstate(under="ignore"):  # products of tiny lever arms and forces flush to zero harmlessly
        W, residuals, cut_points = p.kept.evaluate(oMi)
        Jrows = p.kept.jacobian(W, J)
        if independent_rows is not None:
            _check_regular(p, Jrows, residuals, independent_rows)
        system = _system(p, Jrows)
        x, cond = _solve(p, system, b, determinacy, distribution)
        points = np.concatenate([oMi[:, 1:, :3, 3], cut_points], axis=1)
        reactions = tree_world + _cut_loads(p, p.kept, W, x[:, None, na:], points)[:, 0]
        flags = effort_flags = None
        if determinacy:
            flags, effort_flags = _determinacy(p, oMi, J, points)
    return BatchInverseDynamicsResult(p.joint_names, p.actuated_names, x[:, :na], reactions, p.supports, x[:, na:],
                                      cond, flags, effort_flags)


def inverse_dynamics(p: InverseDynamicsProblem, q: np.ndarray, v: np.ndarray, a: np.ndarray,
                     fext: pin.StdVec_Force | list[pin.Force] | None = None, determinacy: bool = True,
                     distribution: str = "min_norm", independent_rows: int | None = None) -> InverseDynamicsResult:
    """One sample of `inverse_dynamics_batch` (q (nq,), v and a (nv,), fext per joint or None), as dicts."""
    out = inverse_dynamics_batch(p, np.asarray(q, dtype=float)[None], np.asarray(v, dtype=float)[None],
                                 np.asarray(a, dtype=float)[None], [fext], determinacy, distribution, independent_rows)
    return out.sample(0)
