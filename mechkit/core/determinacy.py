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
from mechkit.core.rank import RANK_TOL, ranks

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

    Rows R0 of A, independent at the first sample seen (cached on the data), give by one QR,
    A[R0]^T = Q R, the null space Q[:, r0:] of A[R0]. It is A's null space exactly when a sample
    passes two bounds, which also make the SVD's rank decision r0: sigma_r0(A) >= sigma_min(R) >=
    1 / |R^-1|_F > RANK_TOL |A|_F >= RANK_TOL sigma_1(A) (rank at least r0) and, N = Q[:, r0:] being
    orthonormal, sigma_(r0+1)(A) <= |A N|_F <= RANK_TOL |A|_F / sqrt(nv) <= RANK_TOL sigma_1(A) (at
    most r0). A sample that fails either (a special configuration) gets the SVD, and so does a single
    small sample (`SMALL_SYSTEM`). Either basis spans the same space, and the determinacy depends only
    on that space.

    Args:
        cd: the closure data (caches the independent rows R0 in `stress_rows`).
        A: (N, nv, cols) the matrices [S^T, J_full^T].

    Returns:
        (N, cols, K) orthonormal null-space bases, zero-padded where a sample's null space is smaller.
    """
    n, nv, cols = A.shape
    if n == 0:
        return np.zeros((0, cols, 0))
    if n == 1 and nv * cols <= SMALL_SYSTEM:
        return svd_null_spaces(A)
    if cd.stress_rows is None:
        A0 = A[0]
        r = int(ranks(np.linalg.svd(A0, compute_uv=False)[None])[0])
        cd.stress_rows = np.sort(scipy.linalg.qr(A0.T, mode="r", pivoting=True)[1][:r])
    r0 = cd.stress_rows.size
    if r0 == 0 or r0 == cols:
        return svd_null_spaces(A)
    Q, R = np.linalg.qr(A[:, cd.stress_rows].transpose(0, 2, 1), mode="complete")
    null = Q[:, :, r0:]
    size = np.sqrt(np.einsum("nij,nij->n", A, A))
    try:
        inverse_size = np.sqrt(np.square(np.linalg.inv(R[:, :r0])).sum(axis=(1, 2)))
        ok = (inverse_size * size < 1.0 / RANK_TOL) & (
            np.sqrt(np.square(A @ null).sum(axis=(1, 2))) <= RANK_TOL * size / np.sqrt(nv)
        )
    except np.linalg.LinAlgError:
        ok = np.zeros(n, dtype=bool)
    if ok.all():
        return null
    fallback = svd_null_spaces(A[~ok])
    out = np.zeros((n, cols, max(cols - r0, fallback.shape[2])))
    out[ok, :, : cols - r0] = null[ok]
    out[~ok, :, : fallback.shape[2]] = fallback
    return out


def determinacy(
    cm: ClosureModel,
    cd: ClosureData,
    G: np.ndarray,
    J: np.ndarray,
    q: np.ndarray,
    origins: np.ndarray,
    cut_points: np.ndarray,
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

    Returns:
        (N, njoints - 1 + ncuts, 6) True where a reaction component is determinate (tree joints in
        model order, then the cuts, as `ClosureKernel.joint_loads`), and (N, na) True where an
        actuator's effort is.
    """
    na = len(cm.actuated)
    full = cm.full_kernel
    Wf = full.row_wrenches(G)
    null = self_stresses(cd, system(cm, full.jacobian(Wf, J, q)))
    loads = full.joint_loads(Wf[:, None], null[:, na:].transpose(0, 2, 1), origins[:, None], cut_points[:, None])
    variation = np.sqrt(np.square(loads).sum(axis=1))
    effort_variation = np.sqrt(np.square(null[:, :na]).sum(axis=2))
    scale = np.maximum(np.maximum(variation.max(axis=(1, 2)), effort_variation.max(axis=1, initial=0.0)), 1e-300)
    tol = DETERMINACY_TOL * scale
    return variation <= tol[:, None, None], effort_variation <= tol[:, None]
