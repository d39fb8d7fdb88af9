"""The exact forward dynamics of large mechanisms: the null-space solve on the partition of the closure
Jacobian kept on the data, certified by what its answer satisfies instead of by bounds computed first.

With rows R of J independent and D |R| columns of them forming a regular square block J[R, D], every
acceleration satisfying the rows R is a = a_p + N z, N = [I; -J[R, D]^-1 J[R, I]] (the other columns I
free) and a_p = -J[R, D]^-1 gamma_R, and the dynamics on that set is N^T M N z = N^T (tau - nle - M a_p).
The answer is exact when it satisfies every row, J a + gamma = 0 to the core's tolerance (the caller's
check): then it solves M a + nle = tau + J_R^T lambda and J a + gamma = 0, which with N^T M N positive
definite has one solution in a, whatever the rank of J. So no bound on the rank is needed before the
solve (`mechkit.core.null_space.partitioned_null_space` computes J[R, D]^-1 for one, which on the
66-coordinate truss costs as much as the solve); the pivots of J[R, D]'s LU only keep the solve
accurate (`PIVOT_RATIO`). Where the answer misses a row (a row R does not span: the rank changed, or
gamma leaves the range of J: no rigid answer), the caller hands the state to the bounded path, which
decides by its bounds or the SVD and refuses what has no rigid answer.

Chosen by size, it has no crossover: measured against the bounded path (min of 9 x 100 calls, the
bench's states), it is faster on every registered mechanism, from the four-bar (nv = 3: 59 vs 71 us)
to the 9RR-12URU truss (nv = 66: 162 vs 205 us), with the same accelerations to the last bit (the same
LU and Cholesky), so the exact method ("nullspace") tries it first at every size.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg.blas
import scipy.linalg.lapack

from mechkit.core.model import ClosureData

#: Smallest LU pivot of J[R, D], relative to the largest, that the solve accepts (ours: below it the
#: state goes to the bounded path, whose bound decides whether the rows R are still independent).
PIVOT_RATIO = 1e-10


def solve(cd: ClosureData, J: np.ndarray, gamma: np.ndarray, M: np.ndarray, f: np.ndarray) -> np.ndarray | None:
    """The accelerations a = a_p + N z on the data's partition of J, without bounds (see the module docstring).

    Args:
        cd: the closure data; its `partition` (rows R, dependent columns D, independent columns I), as
            `mechkit.core.null_space.partitioned_null_space` chose it (None: nothing is solved).
        J: (rows, nv) the closure Jacobian.
        gamma: (rows,) its drift.
        M: (nv, nv) the mass matrix, its upper triangle read (Pinocchio's crba).
        f: (nv,) tau - nle, the efforts less the bias forces (N m or N).

    Returns:
        (nv,) accelerations satisfying the rows R exactly (rad/s^2 or m/s^2), to be checked on every row
        by the caller; None without a partition, where J[R, D]'s pivots fall below `PIVOT_RATIO` or where
        N^T M N is not positive definite (a free motion without inertia).
    """
    if cd.partition is None:
        return None
    rows, dep, ind = cd.partition
    lapack, blas = scipy.linalg.lapack, scipy.linalg.blas
    nv = J.shape[1]
    a, N = np.zeros(nv), np.zeros((nv, ind.size))
    N[ind, np.arange(ind.size)] = 1.0
    if rows.size:
        JR = J[rows]
        lu, piv, info = lapack.dgetrf(JR[:, dep])
        pivots = np.abs(lu.diagonal())
        if info or not pivots.min() >= PIVOT_RATIO * pivots.max():
            return None
        X = lapack.dgetrs(lu, piv, np.column_stack((JR[:, ind], gamma[rows])))[0]
        N[dep], a[dep] = -X[:, :-1], -X[:, -1]
    if not ind.size:
        return a
    c, info = lapack.dpotrf(N.T.dot(blas.dsymm(1.0, M, N)))
    if info:
        return None
    a += N.dot(lapack.dpotrs(c, N.T.dot(f - blas.dsymv(1.0, M, a)))[0])
    return a
