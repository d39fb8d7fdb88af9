"""The exact forward dynamics without bounds: the null-space solve on the partition of the closure Jacobian
kept on the data, certified by what its answer satisfies instead of by bounds computed before the solve.

With rows R of J independent and columns D forming a regular square block J[R, D], the accelerations
satisfying the rows R are a = a_p + N z, N = [-J[R, D]^-1 J[R, I]; I] (the other columns I free) and
a_p = -J[R, D]^-1 gamma_R, and the dynamics on them is N^T M N z = N^T (tau - nle - M a_p). The
bounded path (`mechkit.core.null_space.partitioned_null_space`) proves the rank of the rows R by a bound on
J[R, D]^-1, which on the 66-coordinate truss costs a fifth of the call; this solve replaces that bound by a
pivot test on the LU it factors anyway (`PIVOT_RATIO`) and keeps the bounded path's two other tests
(`mechkit.core.null_space.solutions_hold`: J N = 0, so N spans every solution, and gamma in the range of
J, so a state with no rigid answer is refused as before), then requires the answer to close every row to
the core's acceleration tolerance (the strict case of `mechkit.core.forward.check_acceleration`). Such an
answer solves M a + nle = tau + J_R^T lambda and J a + gamma = 0, which with N^T M N positive definite
has one solution in a. A state where a test fails (a rank lost or gained, no rigid answer, a state off
the manifold where a redundant row's drift is not cancelled) is handed to the bounded path, which decides
by its bounds, its drift allowance or the SVD as before (the fast solve's time then adds to its own).

Chosen by size, it has no crossover: against the bounded path alone (the same states, calls alternated,
minima, OPENBLAS_NUM_THREADS=1) it is faster on each of the eight registered mechanisms, nv = 3 to 66
(four-bar 64 vs 77 us, 9RR-12URU truss 237 vs 302 us on a loaded machine; the truss's whole
`Mechanism.forward_dynamics(..., "nullspace")` 186-194 vs 227-234 us in the bench's runs), with the same
accelerations to 2e-13 relative (the same LU and Cholesky, operands ordered differently): the exact method
("nullspace") tries it first at every size.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg.blas
import scipy.linalg.lapack

from mechkit.core import rank
from mechkit.core.model import ClosureData
from mechkit.core.null_space import solutions_hold

#: Smallest LU pivot of J[R, D], relative to the largest, that the solve accepts (ours): three decades above
#: `rank.RANK_TOL`, where the SVD would judge a rank lost; measured at the bench's states, the pivot ratio is
#: 20-60 times sigma_min(J[R, D]) / sigma_1(J) (truss 2e-4 vs 4e-6, tetrahedral unit 8e-5 vs 4.5e-6). Below
#: it the bounded path decides.
PIVOT_RATIO = 1e-6


def solve(
    cd: ClosureData,
    J: np.ndarray,
    gamma: np.ndarray,
    drift: float,
    M: np.ndarray,
    f: np.ndarray,
    tol: float,
) -> np.ndarray | None:
    """The accelerations a = a_p + N z on the data's partition of J, without bounds, where they close every
    row to `tol` (see the module docstring).

    Args:
        cd: the closure data; its `partition` (rows R, dependent columns D, independent columns I), as
            `mechkit.core.null_space.partitioned_null_space` chose it (None: nothing is solved), and the
            `dense_plan` made from it on first use.
        J: (rows, nv) the closure Jacobian.
        gamma: (rows,) its drift.
        drift: the state's closure residual over the rows' lever arm (`mechkit.core.rank.range_limit`).
        M: (nv, nv) the mass matrix, its upper triangle read (Pinocchio's crba, C order).
        f: (nv,) tau - nle, the efforts less the bias forces (N m or N).
        tol: the core's acceleration tolerance (`mechkit.core.forward.ACCELERATION_TOL`): every row must
            close to max |J a + gamma| <= tol (max_i |J_i| max |a| + max |gamma|).

    Returns:
        (nv,) the accelerations (rad/s^2 or m/s^2); None (the bounded path decides) without a partition,
        where J[R, D]'s pivots fall below `PIVOT_RATIO`, where N^T M N is not positive definite (a free
        motion without inertia) or where they do not close every row to `tol` (a row missed: the rank
        changed, gamma leaves the range of J (no rigid answer), or the state is off the manifold).
    """
    if cd.partition is None:
        return None
    if cd.dense_plan is None or cd.dense_plan[0] is not cd.partition:
        cd.dense_plan = _plan(cd.partition, *J.shape)
    _, index, template = cd.dense_plan
    lapack, blas = scipy.linalg.lapack, scipy.linalg.blas
    r, k = index.shape[1], template.shape[1] - 1
    # [N | a_p] (nv, k + 1): its rows D solve J[R, D] [N_D | a_D] = -[J[R, I] | gamma_R], its rows I are [I | 0]
    Na = template.copy()
    if r:
        gathered = np.concatenate((J.ravel(), gamma)).take(index)  # (nv + 1, r): the block's columns, then the rest
        lu, piv, info = lapack.dgetrf(gathered[:r].T, overwrite_a=1)
        pivots = np.abs(lu.diagonal())
        if info or not pivots.min() >= PIVOT_RATIO * pivots.max():
            return None
        Na[cd.partition[1]] = lapack.dgetrs(lu, piv, -gathered[r:].T, overwrite_b=1)[0]
    a, N = Na[:, k].copy(), Na[:, :k]
    if not solutions_hold(J, gamma, a, N, drift):
        return None
    if k:
        MNa = N.T.dot(blas.dsymm(1.0, M.T, Na, lower=1))  # (k, k + 1): N^T M N, then N^T M a_p (M.T: F order)
        c, info = lapack.dpotrf(MNa[:, :k])
        if info:
            return None
        a += N.dot(lapack.dpotrs(c, N.T.dot(f) - MNa[:, k])[0])
    return a if _closes(J, a, gamma, tol) else None


def _closes(J: np.ndarray, a: np.ndarray, gamma: np.ndarray, tol: float) -> bool:
    """Whether dots show max |r| <= tol (max_i |J_i| max |a| + max |gamma|), r = J a + gamma, as |r|^2 rows <=
    tol^2 |gamma|^2 or |r|^2 rows nv <= tol^2 |J|_F^2 |a|^2 implies (a NaN or inf fails both): the strict case
    of `mechkit.core.forward.check_acceleration`, with no allowance for drift or for rows left unsolved."""
    try:
        r = J.dot(a) + gamma
        rr = float(r.dot(r)) * r.size
        return rr <= tol * tol * float(gamma.dot(gamma)) or rr * a.size <= tol * tol * rank.squared_norm(J) * float(
            a.dot(a)
        )
    except FloatingPointError:  # inf - inf under np.errstate(all="raise"): not shown
        return False


def _plan(partition: tuple[np.ndarray, np.ndarray, np.ndarray], size: int, nv: int) -> tuple:
    """(partition, index, template) of `solve` for J of `size` rows and `nv` columns: index (nv + 1, |R|)
    gathers from [J.ravel(), gamma] the columns D of the rows R, then the columns I, then gamma_R
    (transposed: each slice's .T in Fortran order); template (nv, |I| + 1) is [N | a_p] with the rows I
    set, [I | 0], and the rows D zero."""
    rows, dep, ind = partition
    columns = np.concatenate((dep, ind))
    index = np.concatenate((columns[:, None] + nv * rows[None, :], size * nv + rows[None, :]), axis=0)
    template = np.zeros((nv, ind.size + 1))
    template[ind, np.arange(ind.size)] = 1.0
    return partition, index, template
