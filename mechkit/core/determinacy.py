"""Which reaction components and efforts static equilibrium fixes (Wojtyra and Fraczek 2013).

Tested on the cuts' full spatial rows (the physical joints, whatever rows a scene solves with): a
component is determinate when it does not change along the null space of [S^T, J_full^T]; such a
null vector is a self-stress (cut forces, and actuator efforts, in equilibrium with no load). A
component's variation is the norm of its changes along an orthonormal basis of that space, the same
for every basis; determinate: at most `DETERMINACY_TOL` times the largest.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg
import scipy.linalg.lapack

from mechkit.core.model import ClosureData, ClosureModel
from mechkit.core.rank import RANK_TOL, ranks, squared_norm

#: Relative threshold under which a reaction component's null-space variation counts as zero.
DETERMINACY_TOL = 1e-8
#: Entries of [S^T, J_full^T] up to which one sample's self-stresses come from one SVD (cheaper there
#: than the QR with its bounds; see docs/benchmarks.md).
SMALL_SYSTEM = 1000


def system(cm: ClosureModel, Jrows: np.ndarray) -> np.ndarray:
    """The statics matrices [S^T, J^T] of N samples.

    Args:
        cm: the closure model (its actuation S, (na, nv)).
        Jrows: (N, rows, nv) closure Jacobians.

    Returns:
        (N, nv, na + rows) the matrices [S^T, J^T].
    """
    na = len(cm.actuated)
    A = np.empty((Jrows.shape[0], cm.nv, na + Jrows.shape[1]))
    A[:, :, :na] = cm.actuation.T
    A[:, :, na:] = Jrows.transpose(0, 2, 1)
    return A


def svd_null_spaces(A: np.ndarray) -> np.ndarray:
    """Orthonormal null-space bases of N matrices by SVD.

    Args:
        A: (N, nv, cols) matrices.

    Returns:
        (N, cols, K) the right singular vectors past each sample's numerical rank (`rank.ranks`), zero
        columns where a sample's null space is smaller than the largest.
    """
    if len(A) == 1:  # LAPACK directly: a fraction of np.linalg.svd's overhead on one small matrix
        _, s, Vt, _ = scipy.linalg.lapack.dgesdd(A[0], full_matrices=1)
        return Vt[int(ranks(s[None])[0]) :].T[None]
    _, s, Vt = np.linalg.svd(A, full_matrices=True)
    r = ranks(s)
    k, first = Vt.shape[1], int(r.min())
    return np.where((np.arange(first, k)[None, :] >= r[:, None])[..., None], Vt[:, first:], 0.0).transpose(0, 2, 1)


def self_stresses(cd: ClosureData, A: np.ndarray) -> np.ndarray:
    """Orthonormal bases of the null spaces of A = [S^T, J_full^T]: the space `svd_null_spaces` gives,
    mostly without an SVD.

    Where A has full row rank at the first sample seen (the common case: the actuators and the closures
    hold every coordinate), nv columns independent there (cached on the data) give every sample's null
    space by one LU of their square block (`lu_null_spaces`). Elsewhere rows R0 of A, independent at the
    first sample, give by one QR, A[R0]^T = Q R, the null space Q[:, r0:] of A[R0]. It is A's null space exactly when a
    sample passes two bounds, which also make the SVD's rank decision r0: sigma_r0(A) >= sigma_min(R) >=
    1 / |R^-1|_F > RANK_TOL |A|_F >= RANK_TOL sigma_1(A) (rank at least r0) and, N = Q[:, r0:] being
    orthonormal, sigma_(r0+1)(A) <= |A N|_F <= RANK_TOL |A|_F / sqrt(nv) <= RANK_TOL sigma_1(A) (at
    most r0). A sample that fails (a special configuration: the rank changed) gets the SVD, and so does a
    single small sample without the LU path (`SMALL_SYSTEM`). Every basis spans the same space, and the
    determinacy depends only on that space.

    Args:
        cd: the closure data (caches the independent rows R0 in `stress_rows`, the columns in `stress_columns`).
        A: (N, nv, cols) the matrices [S^T, J_full^T].

    Returns:
        (N, cols, K) orthonormal null-space bases, zero-padded where a sample's null space is smaller.
    """
    n, nv, cols = A.shape
    if n == 0:
        return np.zeros((0, cols, 0))
    if cd.stress_rows is None:
        A0 = A[0]
        r = int(ranks(np.linalg.svd(A0, compute_uv=False)[None])[0])
        cd.stress_rows = np.sort(scipy.linalg.qr(A0.T, mode="r", pivoting=True)[1][:r])
        if r == nv:
            columns = np.sort(scipy.linalg.qr(A0, mode="r", pivoting=True)[1][:r])
            free = np.delete(np.arange(cols), columns)
            cd.stress_columns = columns, free, np.eye(cols)[:, np.concatenate([columns, free])]
    r0 = cd.stress_rows.size
    if cd.stress_columns is not None:
        null, ok = lu_null_spaces(A, cd.stress_columns[0])
    elif n == 1 and nv * cols <= SMALL_SYSTEM or r0 == 0 or r0 == cols:
        return svd_null_spaces(A)
    else:
        null, ok = _qr_null_spaces(A, cd.stress_rows)
    if ok.all():
        return null
    fallback = svd_null_spaces(A[~ok])
    out = np.zeros((n, cols, max(null.shape[2], fallback.shape[2])))
    out[ok, :, : null.shape[2]] = null[ok]
    out[~ok, :, : fallback.shape[2]] = fallback
    return out


def lu_null_spaces(A: np.ndarray, columns: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Null-space bases of N matrices of full row rank from one LU of a square block of each.

    With B = A[:, columns] square (nv columns) and F the other columns, Z = [-B^-1 A_F; I] (columns, then
    F) spans the null space of A where B is regular; its QR makes it orthonormal. The bound sigma_nv(A) >=
    sigma_min(B) >= 1 / |B^-1|_F > RANK_TOL |A|_F >= RANK_TOL sigma_1(A) certifies the SVD's rank decision
    (full row rank, so the null space has exactly cols - nv dimensions: Z spans all of it).

    Args:
        A: (N, nv, cols) matrices, cols >= nv.
        columns: (nv,) the columns of the square block.

    Returns:
        (N, cols, cols - nv) orthonormal bases and (N,) whether each sample is certified (a basis of a
        sample that is not is meaningless).
    """
    n, nv, cols = A.shape
    free = np.delete(np.arange(cols), columns)
    k = cols - nv
    if n == 1:
        lapack = scipy.linalg.lapack
        lu, piv, info = lapack.dgetrf(A[0][:, columns])
        inverse = lapack.dgetri(lu, piv)[0] if info == 0 else np.full((nv, nv), np.nan)
        inverse = inverse[None]
    else:
        try:
            inverse = np.linalg.inv(A[:, :, columns])
        except np.linalg.LinAlgError:
            inverse = np.full((n, nv, nv), np.nan)
    with np.errstate(over="ignore", invalid="ignore"):
        ok = np.einsum("nij,nij->n", inverse, inverse) * np.einsum("nij,nij->n", A, A) < RANK_TOL**-2
    Z = np.zeros((n, cols, k))
    X = np.where(ok[:, None, None], inverse, 0.0) @ A[:, :, free]
    Z[:, free, np.arange(k)] = 1.0
    if not X.any():  # zero columns (a planar mechanism's rows out of its plane): Z is orthonormal
        return Z, ok
    Z[:, columns] = -X
    return orthonormal(Z), ok


def orthonormal(Z: np.ndarray) -> np.ndarray:
    """Orthonormal bases of the spaces N matrices' columns span (each of full column rank).

    Args:
        Z: (N, cols, k) matrices, k <= cols, each of rank k.

    Returns:
        (N, cols, k) the Q of their QR (one sample through LAPACK directly).
    """
    if len(Z) == 1 and Z.shape[2]:
        lapack = scipy.linalg.lapack
        qr, tau, _, _ = lapack.dgeqrf(Z[0])
        return lapack.dorgqr(qr, tau)[0][None]
    return np.linalg.qr(Z)[0]


def _qr_null_spaces(A: np.ndarray, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The QR path of `self_stresses`: (N, cols, cols - r0) orthonormal bases and (N,) certified."""
    n, nv, _ = A.shape
    r0 = rows.size
    Q, R = np.linalg.qr(A[:, rows].transpose(0, 2, 1), mode="complete")
    null = Q[:, :, r0:]
    size = np.sqrt(np.einsum("nij,nij->n", A, A))
    try:
        inverse_size = np.sqrt(np.square(np.linalg.inv(R[:, :r0])).sum(axis=(1, 2)))
        ok = (inverse_size * size < 1.0 / RANK_TOL) & (
            np.sqrt(np.square(A @ null).sum(axis=(1, 2))) <= RANK_TOL * size / np.sqrt(nv)
        )
    except np.linalg.LinAlgError:
        ok = np.zeros(n, dtype=bool)
    return null, ok


def determinacy(
    cm: ClosureModel,
    cd: ClosureData,
    G: np.ndarray,
    J: np.ndarray,
    q: np.ndarray,
    origins: np.ndarray,
    cut_points: np.ndarray,
    stresses: np.ndarray | None = None,
    W: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Which reaction components and efforts static equilibrium fixes.

    Args:
        cm: the closure model (its full-row kernel `full_kernel` and actuation).
        cd: the closure data (caches the independent rows of `self_stresses`).
        G: (N, n_used, 4, 4) world placements of the joints carrying cut frames.
        J: (N, 6, nv) joint Jacobians (`data.J`, WORLD frame).
        q: (N, nq) configurations (coupling rows).
        origins: (N, njoints - 1, 3) tree joint origins, in the world frame (m).
        cut_points: (N, ncuts, 3) the cuts' points p_b, in the world frame (m).
        stresses: where the solve already has them (`ClosureModel.spatial`: the scene's rows are the
            full rows), (N, na + rows, K) bases of the null spaces of [S^T, J_full^T], each of full column
            rank and spanning the whole null space (certified by the solve); None: computed here.
        W: (N, cut_size, 6) the full rows' wrenches where the caller has them, else None.

    Returns:
        (N, njoints - 1 + ncuts, 6) True where a reaction component is determinate (tree joints in
        model order, then the cuts, as `ClosureKernel.joint_loads`), and (N, na) True where an
        actuator's effort is.
    """
    na = len(cm.actuated)
    full = cm.full_kernel
    Wf = full.row_wrenches(G) if W is None else W
    if stresses is None:
        null = self_stresses(cd, system(cm, full.jacobian(Wf, J, q)))
    else:
        null = orthonormal(stresses) if stresses.shape[2] else stresses
    if 6 * null.shape[2] <= full.cut_size:  # few self-stresses: their loads; else the map of every row's
        loads = full.joint_loads(Wf[:, None], null[:, na:].transpose(0, 2, 1), origins[:, None], cut_points[:, None])
        variation = np.sqrt(np.square(loads).sum(axis=1))
    else:
        L = full.load_map(Wf, origins, cut_points)
        loads = L.reshape(L.shape[0], 6 * L.shape[1], L.shape[3]) @ null[:, na : na + full.cut_size]
        variation = np.sqrt(np.einsum("nik,nik->ni", loads, loads)).reshape(L.shape[:3])
    effort_variation = np.sqrt(np.square(null[:, :na]).sum(axis=2))
    scale = np.maximum(np.maximum(variation.max(axis=(1, 2)), effort_variation.max(axis=1, initial=0.0)), 1e-300)
    tol = DETERMINACY_TOL * scale
    return variation <= tol[:, None, None], effort_variation <= tol[:, None]


def determinacy_one(
    cm: ClosureModel,
    cd: ClosureData,
    J: np.ndarray,
    q: np.ndarray,
    origins: np.ndarray,
    cut_points: np.ndarray,
    stresses: np.ndarray | None = None,
    W: np.ndarray | None = None,
    world: np.ndarray | None = None,
    statics: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """One sample of `determinacy` (the same flags), from the full rows' world vectors or the joints'
    placements `cd.used` (filled).

    Where the cached columns of `self_stresses` apply, their LU gives the null space; a sample they do
    not certify (the rank changed) gets `self_stresses`, its SVD included.

    Args:
        cm: the closure model.
        cd: the closure data (its placements `used`, filled; caches as `self_stresses`).
        J: (6, nv) joint Jacobians (`data.J`, WORLD frame).
        q: (nq,) configuration (coupling rows).
        origins: (njoints - 1, 3) tree joint origins, world (m).
        cut_points: (ncuts, 3) the cuts' points p_b, world (m).
        stresses: (na + rows, K) a basis of the null space of [S^T, J_full^T] the solve certified, or None
            (see `determinacy`).
        W: (cut_size, 6) the full rows' wrenches where the caller has them, else None.
        world: the full rows' world vectors (`ClosureKernel.world`) where the caller has them, else None.
        statics: (nv, na + full rows) a buffer for [S^T, J_full^T], S^T written (`InversePlan.full_statics`), or None.

    Returns:
        (njoints - 1 + ncuts, 6) and (na,) the flags of `determinacy`.
    """
    na, full = len(cm.actuated), cm.full_kernel
    if world is None:
        world = full.world(cd.used)
    if stresses is None:
        _, Jf, Wf = full.rows(world, J, q)
        if statics is None:
            A = np.concatenate((cm.actuation.T, Jf.T), axis=1)
        else:
            A = statics
            A[:, na:] = Jf.T
        columns = cd.stress_columns
        stresses = None if columns is None else _lu_one(A, *columns)
        null = self_stresses(cd, A[None])[0] if stresses is None else stresses
    else:
        Wf = full.rows(world, J, q)[2] if W is None else W
        null = orthonormal(stresses[None])[0] if stresses.shape[1] else stresses
    if not null.shape[1]:  # no self-stress: statics fixes everything
        return np.ones((origins.shape[0] + cut_points.shape[0], 6), dtype=bool), np.ones(na, dtype=bool)
    K, n = null.shape[1], origins.shape[0] + cut_points.shape[0]
    changes = np.empty((K, 6 * n + na))  # every component's and effort's change along each self-stress
    changes[:, : 6 * n] = full.joint_loads(Wf, null[na:].T, origins, cut_points).reshape(K, 6 * n)
    changes[:, 6 * n :] = null[:na].T
    variation = np.square(changes).sum(axis=0)  # squared, against the squared tolerance
    determinate = variation <= DETERMINACY_TOL**2 * max(float(variation.max()), 1e-300)
    return determinate[: 6 * n].reshape(n, 6), determinate[6 * n :]


def _lu_one(A: np.ndarray, columns: np.ndarray, free: np.ndarray, select: np.ndarray) -> np.ndarray | None:
    """One sample of `lu_null_spaces` on 2-d arrays (`stress_columns`: the square block's columns, the
    others, the permutation matrix putting them first, so that products stand for the gathers):
    (cols, cols - nv) an orthonormal basis, None where the bound does not certify it."""
    nv, cols = A.shape
    gathered = A.dot(select)  # [A[:, columns], A[:, free]]: each entry times 1, plus zeros
    inverse = _lu_inverse(gathered[:, :nv])
    if inverse is None or not squared_norm(inverse) * squared_norm(A) < RANK_TOL**-2:
        return None
    if cols == nv:
        return np.zeros((cols, 0))
    X = inverse.dot(gathered[:, nv:])
    Z = select[:, nv:].copy()  # the unit vectors of the free columns
    if not X.any():  # the other columns are zero (a planar mechanism's rows out of its plane): Z is orthonormal
        return Z
    Z -= select[:, :nv].dot(X)  # -X on the block's columns
    return orthonormal(Z[None])[0]


def _lu_inverse(B: np.ndarray) -> np.ndarray | None:
    """B^-1 by LAPACK getrf and getri; None where B is exactly singular."""
    lapack = scipy.linalg.lapack
    lu, piv, info = lapack.dgetrf(B)
    return None if info else lapack.dgetri(lu, piv)[0]
