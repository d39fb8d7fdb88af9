"""The solutions of the closure rows J a + gamma = 0: a particular solution a_p and a basis N of the null
space of J, every solution being a_p + N z (the tangent space of the constraint manifold that the
null-space forward dynamics solves on).

N comes from one LU of a square block of J where bounds certify the rank and consistency decisions the
SVD would make (the way for many loops: `partitioned_null_space`), else from the SVD (`svd_null_space`),
which refuses a gamma that leaves the range of J.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg
import scipy.linalg.lapack

from mechkit.base.exceptions import InconsistentMotion
from mechkit.core import rank
from mechkit.core.model import ClosureData


def null_space(cd: ClosureData, J: np.ndarray, gamma: np.ndarray, drift: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """a_p and N from the partition kept on the data, else a partition chosen again, else the SVD.

    Args:
        cd: the closure data (keeps the partition between calls).
        J: (rows, nv) the closure Jacobian.
        gamma: (rows,) the closure drift.
        drift: the state's closure residual over the rows' lever arm (`rank.range_limit`).

    Returns:
        a_p (nv,) with J a_p + gamma = 0, and N (nv, nv - rank J) with J N = 0.

    Raises:
        InconsistentMotion: gamma leaves the range of J beyond `rank.range_limit`.
    """
    split = partitioned_null_space(cd, J, gamma, drift=drift)
    split = split or partitioned_null_space(cd, J, gamma, again=True, drift=drift)
    return split if split is not None else svd_null_space(J, gamma, drift)


def partitioned_null_space(
    cd: ClosureData, J: np.ndarray, gamma: np.ndarray, again: bool = False, drift: float = 0.0
) -> tuple[np.ndarray, np.ndarray] | None:
    """a_p and N through one LU of a square block J[R, D], where bounds give the SVD's decisions.

    R are independent rows, then D r independent columns by pivoted QRs (chosen at the first call, or
    `again` at this one, and kept on the data). The bounds: rank r, as sigma_r(J) >= sigma_min(J[R, D]) >=
    1 / |J[R, D]^-1|_F > `rank.RANK_TOL` |J|_F and, N = [I; -J[R, D]^-1 J[R, I]] spanning nv - r dimensions
    with sigma_min(N) >= 1, sigma_(r+1)(J) <= |J N|_F <= RANK_TOL |J|_F / sqrt(min(rows, nv)) <= RANK_TOL
    sigma_1(J); and gamma inside the range of J to `rank.range_limit` (|J a_p + gamma| bounds the part outside).

    Args:
        cd: the closure data (keeps the partition between calls).
        J: (rows, nv) the closure Jacobian.
        gamma: (rows,) the closure drift.
        again: choose the rows and columns again instead of reusing the data's.
        drift: the state's closure residual over the rows' lever arm (`rank.range_limit`).

    Returns:
        (a_p (nv,), N (nv, nv - r)) with J a_p + gamma = 0 and J N = 0; None where a bound fails (the SVD
        decides).
    """
    lapack = scipy.linalg.lapack
    if again or cd.partition is None:
        rows = rank.independent_rows(J)
        columns = np.sort(scipy.linalg.qr(J[rows], mode="r", pivoting=True)[1][: rows.size]) if rows.size else rows
        cd.partition = rows, columns, np.delete(np.arange(J.shape[1]), columns)
    rows, dep, ind = cd.partition
    JR, size = J[rows], rank.squared_norm(J)
    a_p, N = np.zeros(J.shape[1]), np.zeros((J.shape[1], ind.size))
    N[ind] = np.eye(ind.size)
    if rows.size:
        lu, piv, info = lapack.dgetrf(JR[:, dep])
        if info:
            return None
        inverse = lapack.dgetri(lu, piv)[0]
        if not rank.RANK_TOL**2 * rank.squared_norm(inverse) * size < 1.0:
            return None
        X = lapack.dgetrs(lu, piv, np.column_stack((JR[:, ind], gamma[rows])))[0]  # the LU's solve: backward stable
        N[dep], a_p[dep] = -X[:, :-1], -X[:, -1]
    return (a_p, N) if solutions_hold(J, gamma, a_p, N, drift, size) else None


def solutions_hold(
    J: np.ndarray, gamma: np.ndarray, a_p: np.ndarray, N: np.ndarray, drift: float, size: float | None = None
) -> bool:
    """The tests of `partitioned_null_space` after its solve: N = [I; -J[R, D]^-1 J[R, I]] (up to the order of
    the columns) spans all of J's null space where the rows R have rank r, sigma_(r+1)(J) <= |J N|_F <=
    `rank.RANK_TOL` |J|_F / sqrt(min(rows, nv)); and gamma lies in the range of J to `rank.range_limit`.

    Args:
        J: (rows, nv) the closure Jacobian.
        gamma: (rows,) its drift.
        a_p: (nv,) a particular solution of the rows R.
        N: (nv, nv - r) its basis, containing an identity block (so sigma_min(N) >= 1).
        drift: the state's closure residual over the rows' lever arm (`rank.range_limit`).
        size: |J|_F^2 where the caller has it.

    Returns:
        Whether both hold (then every solution of J a + gamma = 0 is a_p + N z).
    """
    size = rank.squared_norm(J) if size is None else size
    if not rank.squared_norm(J.dot(N)) * min(J.shape) <= rank.RANK_TOL**2 * size:
        return False
    outside, g = J.dot(a_p) + gamma, float(np.sqrt(gamma.dot(gamma)))
    return math.sqrt(outside.dot(outside)) <= rank.range_limit(g, g, drift)


def svd_null_space(J: np.ndarray, gamma: np.ndarray, drift: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """The minimum-norm particular solution of J a = -gamma and an orthonormal basis of the null space of
    J, from its SVD.

    Args:
        J: (rows, nv) the closure Jacobian.
        gamma: (rows,) the closure drift.
        drift: the state's closure residual over the rows' lever arm (`rank.range_limit`).

    Returns:
        (a_p (nv,), N (nv, nv - rank J)).

    Raises:
        InconsistentMotion: gamma leaves the range of J beyond `rank.range_limit`.
    """
    U, s, Vt = np.linalg.svd(J, full_matrices=True)
    r = rank.numerical_rank(s)
    outside = float(np.linalg.norm(U[:, r:].T @ gamma)) if J.size else 0.0
    g = float(np.linalg.norm(gamma))
    limit = rank.range_limit(max(g, 1e-300), g, drift)
    if outside > limit:
        raise InconsistentMotion(
            outside,
            limit,
            "forward dynamics (null space): "
            "the closure drift gamma leaves the range of J (the velocity moves along a freedom "
            "that exists only instantaneously)",
        )
    a_p = -(Vt[:r].T @ ((U[:, :r].T @ gamma) / s[:r])) if r else np.zeros(J.shape[1])
    return a_p, Vt[r:].T
