"""The rank judge: numerical rank, regularity of the passive block, singularity, and whether a
right-hand side lies in the range of a matrix, all judged against what the numbers resolve.

Rank decisions are relative to the largest singular value (`RANK_TOL`). Singularity of the passive
block (the closure Jacobian's columns of the coordinates solved for) is judged against the closure
residual the configuration was solved to (`resolvable_singular_value`). A right-hand side outside
the range (an acceleration drift no acceleration cancels) is measured by the least-squares residual
(`outside_range`) and judged against the size of the terms (`RANGE_TOL`).
"""

from __future__ import annotations

import math
from functools import cache

import numpy as np
import scipy.linalg
import scipy.linalg.blas
import scipy.linalg.lapack

from mechkit.base.exceptions import SingularConfiguration

_nrm2 = scipy.linalg.blas.dnrm2

#: Relative singular-value threshold of every numerical rank decision.
RANK_TOL = 1e-9
#: Closure residual the assembly solves to by default (m for position rows).
CLOSURE_TOL = 1e-12
#: Machine epsilon of float64 (the rounding floor of a residual).
EPS = float(np.finfo(float).eps)
#: Margin above the resolvable smallest singular value below which a configuration counts as singular (ours).
SINGULAR_MARGIN = 3.0
#: Largest part of a right-hand side outside a range, relative to the size of the equation's terms (ours).
RANGE_TOL = 1e-8
#: A redundant row's share of gamma per unit of relative drift off the manifold (ours; measured 0.16 on the
#: 9RR-12URU's fold, 2 on the spherical platform's Pinocchio rows on a floating bus).
DRIFT_RANGE_FACTOR = 10.0


def range_limit(terms: float, gamma: float, drift: float) -> float:
    """The largest part of a closure drift gamma outside the range of J that a consistent state explains.

    On the constraint manifold rounding alone puts RANGE_TOL times the terms outside. Off it by a relative
    closure drift d (an integrator's stage, a state not yet projected), a redundant row's left null vector u
    turns by O(d) and gamma, quadratic in the velocities, gets a part u^T gamma of O(d |gamma|) that no
    acceleration cancels (measured on the 9RR-12URU's fold: 1.3e-8 |gamma| at d = 8e-8): the limit is
    RANGE_TOL terms + `DRIFT_RANGE_FACTOR` d |gamma|, so a true inconsistency still fails on the manifold.

    Args:
        terms: the size of the equation's terms (|gamma|, or |J| |a| where larger).
        gamma: |gamma| in the norm of the part measured.
        drift: the closure residual over the rows' lever arm (dimensionless; 0 on the manifold).

    Returns:
        The limit, in gamma's units.
    """
    return RANGE_TOL * terms + DRIFT_RANGE_FACTOR * drift * gamma


def singular_values(A: np.ndarray) -> np.ndarray:
    """Singular values of N matrices (one sample through LAPACK gesdd directly).

    Args:
        A: (N, m, n) matrices.

    Returns:
        (N, min(m, n)) singular values, descending.
    """
    if len(A) == 1 and A.shape[1] and A.shape[2]:
        return scipy.linalg.lapack.dgesdd(A[0], compute_uv=0)[1][None]
    return np.linalg.svd(A, compute_uv=False)


def ranks(s: np.ndarray) -> np.ndarray:
    """Numerical ranks from singular values, relative to the largest (`RANK_TOL`).

    Args:
        s: (N, k) descending singular values.

    Returns:
        (N,) the ranks.
    """
    if s.shape[-1] == 0:
        return np.zeros(len(s), dtype=int)
    return np.sum(s > RANK_TOL * np.maximum(s[:, :1], 1e-290), axis=1)  # a floor whose product does not underflow


def numerical_rank(s: np.ndarray) -> int:
    """Numerical rank from one set of singular values, relative to the largest (`RANK_TOL`).

    Args:
        s: (k,) descending singular values.

    Returns:
        The rank.
    """
    return int(ranks(np.asarray(s)[None])[0])


def independent_rows(J: np.ndarray) -> np.ndarray:
    """A maximal set of linearly independent rows of J (pivoted QR of J^T).

    Args:
        J: (rows, n) matrix.

    Returns:
        The rows' indices, sorted (as many as J's numerical rank).
    """
    if J.shape[0] == 0:
        return np.zeros(0, dtype=int)
    _, r, piv = scipy.linalg.qr(J.T, mode="economic", pivoting=True)
    return np.sort(piv[: numerical_rank(np.abs(np.diag(r)))])


def resolvable_singular_value(s_max: float | np.ndarray, residual: float | np.ndarray) -> float | np.ndarray:
    """The smallest singular value of the passive block that a closure solved to `residual` can resolve.

    Near a singularity the closure residual grows quadratically in the passive coordinates, e ~ s_max
    dx^2, while a regular pose has e ~ s_min dx. A solve that stopped at |e| = r therefore leaves the
    passive coordinates uncertain by sqrt(r / s_max) and cannot tell s_min from zero once s_min is
    below sqrt(r s_max) (same units as the rows: m for position rows). Newton converges only linearly
    at a singular point, so there it stops near its tolerance (`CLOSURE_TOL`), while at a regular pose
    it overshoots to rounding; r is floored at rounding, eps s_max. `SINGULAR_MARGIN` sits above the
    singular floor (measured on the five-bar with its distal links collinear: at the singular input
    s_min is 0.6 to 0.9 sqrt(r s_max); 1e-8 rad away over 30 times that). Element-wise on arrays.

    Args:
        s_max: largest singular value of the passive block (the rows' scale).
        residual: closure residual norm reached at the configuration.

    Returns:
        `SINGULAR_MARGIN` sqrt(max(residual, eps s_max) s_max): a float for floats, else an array.
    """
    if isinstance(s_max, float) and isinstance(residual, float):
        return SINGULAR_MARGIN * math.sqrt(max(residual, EPS * s_max) * s_max)
    return SINGULAR_MARGIN * np.sqrt(np.maximum(residual, EPS * s_max) * s_max)


def passive_verdict(s: np.ndarray, columns: int, residual: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per sample, the passive block's condition number and whether it is not resolvably regular.

    Args:
        s: (N, k) descending singular values of the passive blocks.
        columns: the blocks' column count (coordinates solved for); a unique solution needs that rank.
        residual: (N,) closure residual norms at the configurations.

    Returns:
        (N,) condition numbers s_max / s_min (inf where singular) and (N,) flags, True where s_min is
        below `resolvable_singular_value` or there are fewer rows than columns.
    """
    n = len(s)
    if columns == 0:
        return np.ones(n), np.zeros(n, dtype=bool)
    if s.shape[1] < columns:
        return np.full(n, np.inf), np.ones(n, dtype=bool)
    s_max, s_min = s[:, 0], s[:, columns - 1]
    cond = np.divide(s_max, s_min, out=np.full(n, np.inf), where=s_min > 0)
    bad = s_min < resolvable_singular_value(s_max, residual)
    return cond, bad


def regularity_bounds(B: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Bounds on the extreme singular values of N blocks without an SVD.

    Args:
        B: (N, m, k) blocks.

    Returns:
        (N,) rho = 1 / |X|_F <= sigma_min(m, k) (X = B^-1 where square, else R^-1 of B = Q R, or of
        B^T = Q R where wide; 0 where singular) and (N,) |B|_F >= sigma_max.
    """
    m, k = B.shape[1:]
    try:
        X = np.linalg.inv(B if m == k else np.linalg.qr(B if m > k else B.transpose(0, 2, 1), mode="r"))
    except np.linalg.LinAlgError:  # a singular block: one at a time
        rho, size = np.array([block_bounds(b) for b in B]).reshape(len(B), 2).T
        return rho, size
    with np.errstate(over="ignore", under="ignore"):  # an inverse too large to square: rho 0, as singular
        return np.square(X).sum(axis=(1, 2)) ** -0.5, np.sqrt(np.square(B).sum(axis=(1, 2)))


def block_bounds(B: np.ndarray) -> tuple[float, float]:
    """`regularity_bounds` of one block.

    Args:
        B: (m, k) block.

    Returns:
        rho = 1 / |X|_F <= sigma_min (0 where singular) and |B|_F >= sigma_max.
    """
    m, k = B.shape
    if m == k:
        lu, piv, info = scipy.linalg.lapack.dgetrf(B)
        X = None if info else scipy.linalg.lapack.dgetri(lu, piv)[0]
    else:
        X = triangular_inverse(scipy.linalg.lapack.dgeqrf(B if m > k else B.T)[0], min(m, k))
    return (0.0 if X is None else inverse_norm(X)), squared_norm(B) ** 0.5


def triangular_inverse(qr: np.ndarray, k: int) -> np.ndarray | None:
    """The inverse of the R factor of a LAPACK QR.

    Args:
        qr: LAPACK geqrf's first output; R is the upper triangle of its first k rows.
        k: the size of R.

    Returns:
        (k, k) R^-1, upper triangular; None where R is singular or empty (LAPACK refuses an empty R: it
        printed "DTRTRI parameter number 5 had an illegal value" and gave the same None).
    """
    if k == 0:
        return None
    X, info = scipy.linalg.lapack.dtrtri(qr[:k])
    if info:
        return None
    X *= upper(k)
    return X


def squared_norm(X: np.ndarray) -> float:
    """The squared Frobenius norm of an array.

    Args:
        X: an array of any shape.

    Returns:
        |X|_F^2, the sum of its squared entries (inf where it overflows, whatever the caller's np.errstate:
        the tests it feeds then fail safe, e.g. an inverse too large certifies nothing).
    """
    if not X.size:
        return 0.0
    norm = _nrm2(X.ravel(order="K"))  # BLAS, scaled: no floating-point error state to set, none raised
    return norm * norm  # a Python float: inf where it overflows, 0 where it underflows, silently


def certified_regular(rho: np.ndarray, size: np.ndarray, residual: np.ndarray) -> np.ndarray:
    """Where bounds on the extreme singular values of passive blocks show them resolvably regular and of
    full column rank: the verdict `passive_verdict` then gives on their singular values (the resolvable
    limit grows with sigma_max). Floats, or element-wise on arrays.

    Args:
        rho: lower bounds on sigma_min (`regularity_bounds`).
        size: upper bounds on sigma_max (`regularity_bounds`).
        residual: closure residual norms at the configurations.

    Returns:
        True where rho exceeds both `resolvable_singular_value`(size, residual) and `RANK_TOL` size.
    """
    return (rho > resolvable_singular_value(size, residual)) & (rho > RANK_TOL * size)


def inverse_norm(X: np.ndarray) -> float:
    """1 / |X|_F (X the inverse of a matrix: a lower bound on that matrix's smallest singular value).

    Args:
        X: an array of any shape.

    Returns:
        1 / |X|_F: 0 where |X|_F overflows (no bound: the caller's test fails safe), inf where it is 0.
    """
    norm = _nrm2(X.ravel(order="K")) if X.size else 0.0
    return 1.0 / norm if norm else math.inf


@cache
def upper(k: int) -> np.ndarray:
    """The mask of an upper-triangular LAPACK result (cached per size).

    Args:
        k: the size.

    Returns:
        (k, k) ones on and above the diagonal, zeros below.
    """
    return np.triu(np.ones((k, k)))


def singular_error(s: np.ndarray, columns: int, residual: float) -> SingularConfiguration:
    """The error for a passive block that `passive_verdict` rejects (returned, not raised).

    Args:
        s: (k,) descending singular values of the passive block.
        columns: the block's column count (coordinates solved for).
        residual: closure residual norm at the configuration.

    Returns:
        A `SingularConfiguration` saying why: fewer rows than columns, a rank below the column count,
        or a smallest singular value below what the residual resolves.
    """
    if s.size < columns:
        return SingularConfiguration(
            float("inf"),
            f"{columns} coordinates to solve for but only {s.size} closure rows: "
            "the inputs do not determine the motion (give more inputs)",
        )
    cond, _ = passive_verdict(s[None], columns, np.array([residual]))
    s_min = s[columns - 1]
    rank = numerical_rank(s)
    if rank < columns:
        return SingularConfiguration(
            float(cond[0]),
            f"the closure determines only {rank} of the {columns} coordinates "
            "solved for: the inputs do not determine the motion (give more inputs, or the pose "
            "is singular)",
        )
    limit = resolvable_singular_value(s[0], residual)
    return SingularConfiguration(
        float(cond[0]),
        f"passive block of the closure Jacobian: smallest singular value "
        f"{s_min:.2e} below the {limit:.2e} a closure residual of {residual:.1e} resolves "
        "(inputs do not determine the motion)",
    )


def check_passive(s: np.ndarray, columns: int, residual: np.ndarray | float) -> np.ndarray:
    """Condition numbers of N passive blocks; raise at the first sample `passive_verdict` rejects.

    Args:
        s: (N, k) descending singular values of the passive blocks.
        columns: the blocks' column count (coordinates solved for).
        residual: (N,) closure residual norms, or one for every sample.

    Returns:
        (N,) condition numbers s_max / s_min.

    Raises:
        SingularConfiguration: naming the smallest singular value and what the residual resolves.
    """
    residual = np.broadcast_to(np.asarray(residual, dtype=float), (len(s),))
    cond, bad = passive_verdict(s, columns, residual)
    if bad.any():
        i = int(np.argmax(bad))
        raise singular_error(s[i], columns, float(residual[i]))
    return cond


def outside_range(U: np.ndarray, rank: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The size of the part of right-hand sides outside the range of N matrices.

    Args:
        U: (N, m, m) the matrices' full left singular vectors.
        rank: (N,) their ranks.
        b: (N, m) right-hand sides.

    Returns:
        (N,) the norms of the parts of b outside the ranges.
    """
    proj = np.einsum("nij,ni->nj", U, b)
    return np.sqrt(np.square(np.where(np.arange(proj.shape[1])[None, :] >= rank[:, None], proj, 0.0)).sum(axis=1))


def inconsistency(J: np.ndarray, gamma: np.ndarray) -> float:
    """How far no acceleration satisfies every row, by a complete orthogonal factorisation (LAPACK gelsy).

    Args:
        J: (rows, nv) closure Jacobian.
        gamma: (rows,) closure drift.

    Returns:
        max |J a + gamma| at the least-squares a: 0 (to rounding) when gamma is in the range of J.
    """
    if J.shape[0] == 0:
        return 0.0
    x = scipy.linalg.lstsq(J, -gamma, cond=EPS * max(J.shape), lapack_driver="gelsy")[0]
    return float(np.abs(J @ x + gamma).max())
