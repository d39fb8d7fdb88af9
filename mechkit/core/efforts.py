"""The statics of inverse dynamics: efforts and multipliers x = [u; lambda] with [S^T, J^T] x = b.

S is the actuation, J the closure rows, b the generalised force the motion needs (rnea minus passive
forces). Where every actuator is one joint's motor and the passive block B = J[:, passive] has more
rows than columns (a redundant row), the system splits (`passive_solve`): B^T lambda = b_passive,
u = b_actuated - J_actuated^T lambda, and one LU of a square part of B certifies the block regular and
[S^T, J^T] of full row rank and gives the minimum-norm solution. Elsewhere `solve`: LAPACK gesv where [S^T, J^T]
is square, QR where it has full rank, an SVD otherwise (moved to the least efforts for "min_effort").
One sample and N samples give the same numbers.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg
import scipy.linalg.lapack

from mechkit.base.exceptions import SingularConfiguration
from mechkit.core import rank
from mechkit.core.model import ClosureData, ClosureModel


def splits(cm: ClosureModel, rows: int, distribution: str) -> bool:
    """Whether `passive_solve` applies.

    Args:
        cm: the closure model (its `passive_v`, set where every actuator is one joint's motor).
        rows: number of closure rows.
        distribution: "min_norm" or "min_effort".

    Returns:
        True where every actuator is one joint's motor, the passive block has more rows than columns
        (a redundant row), and the minimum-norm solution is asked for.
    """
    return cm.passive_v is not None and 0 < cm.passive_v.size < rows and distribution == "min_norm"


def passive_solve(
    cm: ClosureModel, cd: ClosureData, Jrows: np.ndarray, b: np.ndarray, residuals: np.ndarray
) -> tuple[np.ndarray | None, np.ndarray]:
    """The minimum-norm [u; lambda] of N samples through one LU of each passive block's square part.

    Args:
        cm: the closure model.
        cd: the closure data (caches the passive block's independent rows).
        Jrows: (N, rows, nv) closure Jacobians.
        b: (N, nv) generalised forces the motion needs.
        residuals: (N,) closure residual norms (for `rank.certified_regular`).

    Returns:
        x (N, na + rows), None where some sample's [S^T, J^T] is not certified of full row rank; and
        (N,) whether each passive block is certified resolvably regular (`passive_one`).
    """
    return passive_split_batch(cm, cd, Jrows, b, residuals)[:2]


def passive_split_batch(
    cm: ClosureModel, cd: ClosureData, Jrows: np.ndarray, b: np.ndarray, residuals: np.ndarray
) -> tuple[np.ndarray | None, np.ndarray, np.ndarray | None]:
    """`passive_solve`, and the null spaces of [S^T, J^T] (`passive_split`).

    Args:
        cm: the closure model.
        cd: the closure data (caches the passive block's independent rows).
        Jrows: (N, rows, nv) closure Jacobians.
        b: (N, nv) generalised forces the motion needs.
        residuals: (N,) closure residual norms (for `rank.certified_regular`).

    Returns:
        x (N, na + rows) and (N, na + rows, rows - k) bases of the null spaces, both None where some
        sample's [S^T, J^T] is not certified of full row rank; and (N,) whether each passive block is
        certified resolvably regular.
    """
    out = [passive_split(cm, cd, Jrows[i], b[i], float(residuals[i])) for i in range(len(Jrows))]
    regular = np.array([r for _, r, _ in out], dtype=bool)
    if any(x is None for x, _, _ in out):
        return None, regular, None
    cols = len(cm.actuated) + Jrows.shape[1]
    null = np.array([z for _, _, z in out]).reshape(len(out), cols, -1 if out else 0)
    return np.array([x for x, _, _ in out]).reshape(len(out), cols), regular, null


def passive_one(
    cm: ClosureModel, cd: ClosureData, J: np.ndarray, b: np.ndarray, residual: float
) -> tuple[np.ndarray | None, bool]:
    """One sample of `passive_solve` (`passive_split` without the null space).

    Args:
        cm: the closure model.
        cd: the closure data (caches the independent rows of B in `split_rows`).
        J: (rows, nv) closure Jacobian.
        b: (nv,) generalised force the motion needs.
        residual: closure residual norm (for `rank.certified_regular`).

    Returns:
        x (na + rows,), None where [S^T, J^T] is not certified of full row rank; and whether the passive
        block is certified resolvably regular.
    """
    return passive_split(cm, cd, J, b, residual)[:2]


def passive_split(
    cm: ClosureModel, cd: ClosureData, J: np.ndarray, b: np.ndarray, residual: float
) -> tuple[np.ndarray | None, bool, np.ndarray | None]:
    """One sample of `passive_solve`, and the null space of [S^T, J^T] its factorisation gives.

    With every actuator one joint's motor, [S^T, J^T] x = b splits into B^T lambda = b_p and u = b_a -
    J_a^T lambda, B = J[:, passive] (rows > columns). Rows s of B forming a regular square block B_s
    (independent at the first sample, kept on the data) give lambda = lambda_0 + N t: lambda_0 = B_s^-T b_p
    on s, N = [-B_s^-T B_x^T; I] on (s, the others x), both by the LU's solves (backward stable; the
    explicit inverse serves the bounds only). |u|^2 + |lambda|^2 is least at (K^T K + N^T N) t =
    K^T (b_a - J_a^T lambda_0) - N^T lambda_0, K = J_a^T N: the minimum-norm solution. The inverse also
    bounds sigma_min(B) >= sigma_min(B_s) >= 1 / |B_s^-1|_F, and [S^T, J^T] has the right inverse
    [[I, -J_a^T Y], [0, Y]], Y = B_s^-T on s: sigma_min >= (na + (1 + |J_a|_F^2) |B_s^-1|_F^2)^(-1/2)
    against sigma_max <= (na + |J|_F^2)^(1/2), whose ratio above `rank.RANK_TOL` certifies full row rank.
    [S^T, J^T] x = 0, x = (u, lambda), is then lambda = N t, u = -J_a^T N t: [-K; N] spans its null space (the
    self-stresses), of rows - (nv - na) dimensions.

    Args:
        cm: the closure model.
        cd: the closure data (caches the independent rows of B in `split_rows`).
        J: (rows, nv) closure Jacobian.
        b: (nv,) generalised force the motion needs.
        residual: closure residual norm (for `rank.certified_regular`).

    Returns:
        x (na + rows,), None where [S^T, J^T] is not certified of full row rank; whether the passive
        block is certified resolvably regular (`rank.certified_regular`); and (na + rows, rows - k) a
        basis of the null space of [S^T, J^T] (None with x None).
    """
    lapack = scipy.linalg.lapack
    act, free = cm.actuated_v, cm.passive_v
    B, Ja = J[:, free], J[:, act]
    m, k = B.shape
    if cd.split_rows is None:
        rows = rank.independent_rows(B)
        cd.split_rows = rows, np.delete(np.arange(m), rows)
    rows, others = cd.split_rows
    if rows.size != k:
        return None, False, None
    lu, piv, info = lapack.dgetrf(B[rows])
    if info:
        return None, False, None
    inverse = lapack.dgetri(lu, piv)[0]
    inverse_size, size, actuated_size = rank.squared_norm(inverse), rank.squared_norm(B), rank.squared_norm(Ja)
    regular = bool(rank.certified_regular(inverse_size**-0.5 if inverse_size else math.inf, size**0.5, residual))
    if (
        not rank.RANK_TOL**2 * (act.size + (1.0 + actuated_size) * inverse_size) * (act.size + size + actuated_size)
        < 1.0
    ):
        return None, regular, None
    lam, N = np.zeros(m), np.zeros((m, m - k))
    solved = lapack.dgetrs(lu, piv, np.column_stack((b[free], -B[others].T)), trans=1)[0]  # B_s^-T [b_p, -B_x^T]
    lam[rows], N[rows] = solved[:, 0], solved[:, 1:]
    N[others] = np.eye(m - k)
    ba, JaT = b[act], Ja.T
    K = JaT.dot(N)
    t = lapack.dgesv(K.T.dot(K) + N.T.dot(N), K.T.dot(ba - JaT.dot(lam)) - N.T.dot(lam))[2]
    lam += N.dot(t)
    return np.concatenate([ba - JaT.dot(lam), lam]), regular, np.concatenate([-K, N])


def square_one(A: np.ndarray, b: np.ndarray, bound: bool) -> tuple[np.ndarray | None, float]:
    """One sample of a square system [S^T, J^T] x = b (na + rows = nv): gesv
    (the numbers `square_solution` gives) and, with `bound`, 1 / |A^-1|_F from its LU (getri).

    That bounds sigma_min(A) and the passive block's smallest singular value: B^-T = [A^-1]_lambda U
    (U the orthonormal unactuated basis), so sigma_min(B) >= 1 / |A^-1|_2 >= 1 / |A^-1|_F.

    Args:
        A: (nv, nv) the matrix [S^T, J^T] (not changed).
        b: (nv,) generalised force the motion needs.
        bound: also compute the bound 1 / |A^-1|_F.

    Returns:
        x (nv,), None where A is singular or x not finite; the bound (0 without `bound` or where singular).
    """
    lapack = scipy.linalg.lapack
    lu, piv, x, info = lapack.dgesv(A, b)
    if info or not (math.isfinite(x.dot(x)) or np.isfinite(x).all()):
        return None, 0.0
    return x, (rank.inverse_norm(lapack.dgetri(lu, piv)[0]) if bound else 0.0)  # overflow: 0, the SVD decides


def square_bounds(A: np.ndarray) -> np.ndarray:
    """`square_one`'s bound of N square systems: 1 / |A^-1|_F <= sigma_min(A), which also bounds each
    passive block's smallest singular value.

    Args:
        A: (N, nv, nv) the matrices [S^T, J^T].

    Returns:
        (N,) the bounds (0 where some A is singular or its inverse too large to square: no bound).
    """
    try:
        inverse = np.linalg.inv(A)
    except np.linalg.LinAlgError:
        return np.zeros(len(A))
    with np.errstate(over="ignore", under="ignore", divide="ignore"):
        return np.square(inverse).sum(axis=(1, 2)) ** -0.5  # inf ** -0.5 = 0


def singular(A: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Singular values, numerical ranks and condition numbers of N matrices.

    Args:
        A: (N, nv, cols) matrices.

    Returns:
        Singular values (N, k), numerical ranks (N,) and condition numbers s_max / s_rank (N,).
    """
    s = rank.singular_values(A)
    r = rank.ranks(s)
    return s, r, s[:, 0] / s[np.arange(len(s)), np.maximum(r, 1) - 1]


def solve(
    cm: ClosureModel, A: np.ndarray, b: np.ndarray, condition: bool, distribution: str
) -> tuple[np.ndarray, np.ndarray]:
    """x (N, cols) with A x = b, and the condition numbers (N,) (nan when `condition` is False).

    Square systems: gesv (with `condition`, after singular values that show every sample regular).
    Otherwise, where every sample has full rank and the solution is unique (or minimum-norm is asked
    for), the least-squares / minimum-norm solution by QR (without `condition`, its R bounding
    sigma_min(A) above `rank.RANK_TOL` |A|_F shows the full rank the singular values would); else by
    SVD, moved to the least efforts for "min_effort". Either way the same unique x, and b must be
    reachable.

    Args:
        cm: the closure model (its number of actuators, for "min_effort").
        A: (N, nv, cols) the matrices [S^T, J^T].
        b: (N, nv) generalised forces the motion needs.
        condition: compute the condition numbers (by an SVD).
        distribution: "min_norm" or "min_effort": which solution where it is not unique.

    Returns:
        x (N, cols) = [u; lambda], and the condition numbers (N,) (nan when `condition` is False).

    Raises:
        SingularConfiguration: b is not reachable (outside the range of A) for some sample.
    """
    n, nv, cols = A.shape
    if cols == 0:  # no actuator and no closure row: the motion must need no force at all
        _check_reachable(A, np.linalg.norm(b, axis=1), b)
        return np.zeros((n, 0)), np.full(n, np.nan)
    square = nv == cols
    if square and not condition:
        try:
            return square_solution(A, b), np.full(n, np.nan)
        except SingularConfiguration:
            pass  # rank deficient (idle freedoms): the SVD below
    unique = distribution == "min_norm" or cols < nv
    if not square and not condition and unique:
        x, outside, rho = full_rank_solution(A, b)
        if np.all(rho > rank.RANK_TOL * np.sqrt(np.square(A).sum(axis=(1, 2)))):  # the SVD's rank: full
            _check_reachable(A, outside, b)
            return x, np.full(n, np.nan)
    s, r, cond = singular(A)
    full = bool(np.all(r == min(nv, cols)))
    if square and full:
        return square_solution(A, b), cond
    if full and unique:
        x, outside, _ = full_rank_solution(A, b)
        _check_reachable(A, outside, b)
        return x, cond
    U, s, Vt = np.linalg.svd(A, full_matrices=True)
    k = s.shape[1]
    keep = np.arange(k)[None, :] < r[:, None]
    proj = np.einsum("nij,ni->nj", U, b)
    _check_reachable(A, rank.outside_range(U, r, b), b)
    coef = np.where(keep, proj[:, :k] / np.where(keep, s, 1.0), 0.0)
    x = np.einsum("nij,ni->nj", Vt[:, :k], coef)
    if distribution == "min_effort":
        na = len(cm.actuated)
        for i in np.flatnonzero(r < cols):
            x[i] = _least_effort(x[i], Vt[i, r[i] :].T, na)
    return x, cond


def square_solution(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Solve N square systems A x = b by gesv.

    Args:
        A: (N, n, n) square matrices.
        b: (N, n) right-hand sides.

    Returns:
        (N, n) the solutions x.

    Raises:
        SingularConfiguration: some A is singular (or its solution is not finite).
    """
    n, cols = A.shape[0], A.shape[2]
    if n == 1:  # LAPACK gesv directly: a fraction of np.linalg.solve's overhead on small systems
        _, _, x, info = scipy.linalg.lapack.dgesv(A[0], b[0])
        if info == 0 and (math.isfinite(x.dot(x)) or np.isfinite(x).all()):  # the sum of squares first: one call
            return x[None]
        x = np.full((1, cols), np.nan)
    else:
        try:
            x = np.linalg.solve(A, b[..., None])[..., 0]
        except np.linalg.LinAlgError:
            x = np.full((n, cols), np.nan)
    if not np.all(np.isfinite(x)):
        raise SingularConfiguration(float("inf"), "[S^T, J^T]: efforts and multipliers undetermined")
    return x


def full_rank_solution(A: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The unique least-squares (full column rank) or minimum-norm (full row rank) solution of A x = b by QR.

    Args:
        A: (N, nv, cols) matrices, each of full rank.
        b: (N, nv) right-hand sides.

    Returns:
        x (N, cols); the norm (N,) of the part of b outside the range of A; and (N,) 1 / |R^-1|_F <=
        sigma_min(A) (0 where R is singular).
    """
    if len(A) == 1:  # LAPACK directly: a fraction of np.linalg's overhead on one small matrix
        x, outside, rho = _full_rank_one(A[0], b[0])
        return x[None], np.array([outside]), np.array([rho])
    tall = A.shape[1] > A.shape[2]
    Q, R = np.linalg.qr(A if tall else A.transpose(0, 2, 1))  # A = Q R: x = R^-1 Q^T b; A^T = Q R: x = Q R^-T b
    try:
        if tall:
            c = np.einsum("nij,ni->nj", Q, b)
            x = np.linalg.solve(R, c[..., None])[..., 0]
            outside = np.linalg.norm(b - np.einsum("nij,nj->ni", Q, c), axis=1)
        else:  # every b reachable
            x, outside = (Q @ np.linalg.solve(R.transpose(0, 2, 1), b[..., None]))[..., 0], np.zeros(len(A))
    except np.linalg.LinAlgError:  # an exactly singular R: no solution here, and no bound
        return np.full((len(A), A.shape[2]), np.nan), np.full(len(A), np.inf), np.zeros(len(A))
    return x, outside, rank.regularity_bounds(R)[0]


def _full_rank_one(A: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, float, float]:
    """One sample of `full_rank_solution`: LAPACK geqrf, ormqr, trtrs and trtri on 2-d arrays."""
    lapack = scipy.linalg.lapack
    m, n = A.shape
    k = min(m, n)
    qr, tau, _, _ = lapack.dgeqrf(A if m > n else A.T)  # A = Q R (tall) or A^T = Q R
    R, X = qr[:k], rank.triangular_inverse(qr, k)  # trtrs reads R's upper triangle only
    if X is None:  # an exactly singular R: no solution here, and no bound
        return np.full(n, np.nan), math.inf, 0.0
    if m > n:
        c = lapack.dormqr("L", "T", qr, tau, b[:, None], max(1, m))[0][:, 0]
        x = lapack.dtrtrs(R, c[:k])[0]
        return x, rank.squared_norm(c[k:]) ** 0.5, rank.inverse_norm(X)
    y = lapack.dtrtrs(R, b, trans=1)[0]  # R^T y = b
    z = np.zeros(n)
    z[:k] = y
    return lapack.dormqr("L", "N", qr, tau, z[:, None], max(1, n))[0][:, 0], 0.0, rank.inverse_norm(X)


def _check_reachable(A: np.ndarray, outside: np.ndarray, b: np.ndarray) -> None:
    """`SingularConfiguration` where the part of b outside the range of [S^T, J^T] (A) is not
    negligible: the actuators cannot hold the motion."""
    bad = np.flatnonzero(outside > 1e-9 * np.maximum(np.linalg.norm(b, axis=1), 1.0))
    if bad.size:
        i = int(bad[0])
        s = rank.singular_values(A[i][None])[0] if A.shape[2] else np.zeros(1)
        raise SingularConfiguration(
            float(s[0] / s[-1]) if s[-1] > 0 else float("inf"),
            f"[S^T, J^T] does not span the required generalised force (sample {i}): the "
            "actuators cannot hold this motion",
        )


def _least_effort(x: np.ndarray, N: np.ndarray, na: int) -> np.ndarray:
    """Move x along the null space N to the smallest efforts |u|, then the smallest multipliers."""
    z = -np.linalg.lstsq(N[:na], x[:na], rcond=None)[0]
    x = x + N @ z
    keep = N @ scipy.linalg.null_space(N[:na]) if na else N
    if keep.size:
        x = x - keep @ np.linalg.lstsq(keep[na:], x[na:], rcond=None)[0]
    return x
