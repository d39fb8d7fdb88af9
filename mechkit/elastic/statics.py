"""The force method over the rigid mechanism: equilibrium at a pose, and compatibility.

Unknowns x = [u; lambda]: the efforts (actuators, then the joint springs the idealisation treats as
drives) and the multipliers of every cut's full spatial rows (the physical joints). Equilibrium is
the rigid one, A x = b with A = [S^T, S_springs^T, J_full^T]; every solution is x_p + N z, N a basis of
the self-stresses (the null space of A). The reactions R(x) and efforts u are linear in x. Of all
equilibria the compatible one minimises the complementary energy
U*(z) = 1/2 sum_j R_j^T F_j R_j + 1/2 sum_k c_k u_k^2 (joint compliances F_j, drive compliances c_k):
(Y^T F Y) z = -Y^T F r_p with Y the reactions and efforts of the self-stresses. Components along the
null space of Y^T F Y (self-stresses that strain nothing elastic) stay indeterminate.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.elastic.idealisation import Idealisation

#: Closure residual (m, or rad for alignment rows) above which a pose counts as not assembled.
CLOSED_TOL = 1e-8
#: Relative tolerance of the equilibrium residual of a particular solution (the load must be held).
HELD_TOL = 1e-9
#: Relative eigenvalue of Y^T F Y under which a self-stress counts as straining nothing elastic.
STRAIN_TOL = 1e-10


@dataclass(frozen=True)
class Pose:
    """The rigid statics of N poses.

    Attributes:
        q: (N, nq) the poses.
        R: (N, njoints, 3, 3) body rotations (world).
        t: (N, njoints, 3) body origins (world, m).
        J: (N, 6, nv) world joint Jacobians (Pinocchio's `data.J`).
        points: (N, n_joints, 3) the reactions' points (tree joint origins, then cut frame_b origins).
        A: (N, nv, m) equilibrium matrix [S^T, S_springs^T, J_full^T].
        reaction_map: (N, n_joints, 6, m) reactions per unit of each unknown (effort columns: zero).
        null: (N, m, s) orthonormal self-stress bases (zero columns where a sample's space is smaller).
        compliance: (N, n_joints, 6, 6) joint compliances at the reactions' points (`Idealisation.compliances`).
        efforts: number of effort columns at the front of x (actuators, then spring drives).
    """

    q: np.ndarray
    R: np.ndarray
    t: np.ndarray
    J: np.ndarray
    points: np.ndarray
    A: np.ndarray
    reaction_map: np.ndarray
    null: np.ndarray
    compliance: np.ndarray
    efforts: int


def evaluate(ideal: Idealisation, Q: np.ndarray, actuation: np.ndarray | None = None) -> Pose:
    """The rigid statics of N poses.

    Args:
        ideal: the idealisation (its mechanism and scratch data).
        Q: (N, nq) poses, which must close the loops.
        actuation: (na, nv) the drives' S (default the mechanism's actuators); the idealisation's spring
            drives follow them.

    Returns:
        The `Pose`.

    Raises:
        InvalidParameters: a pose that does not close the loops (residual over `CLOSED_TOL`).
    """
    mech = ideal.mech
    cm, model = mech.closure_model, mech.model
    S = cm.actuation if actuation is None else actuation
    na = len(S)
    n, nj = len(Q), model.njoints
    data = ideal.pin_data
    R = np.empty((n, nj, 3, 3))
    t = np.empty((n, nj, 3))
    J = np.empty((n, 6, model.nv))
    rotations, translations = ideal.pin_rotations, ideal.pin_translations
    for i in range(n):
        pin.computeJointJacobians(model, data, Q[i])
        J[i] = data.J.reshape(6, -1)  # Pinocchio gives (6,) when nv = 1
        R[i] = rotations
        t[i] = translations
    full = cm.full_kernel
    used = full.joints
    G = np.zeros((n, used.size, 4, 4))
    G[..., :3, :3], G[..., :3, 3], G[..., 3, 3] = R[:, used], t[:, used], 1.0
    residual = np.abs(full.residual(G, Q)).max(initial=0.0)
    if residual > CLOSED_TOL:
        raise InvalidParameters(
            "q",
            f"closure residual {residual:.3g}",
            f"the pose does not close the loops (over "
            f"{CLOSED_TOL:g}): the elastic model is linear about an assembled pose",
        )
    W = full.row_wrenches(G)
    rows = full.jacobian(W, J, Q)
    ne = na + len(ideal.drives)
    m = ne + full.size
    A = np.empty((n, model.nv, m))
    A[:, :, :na] = S.T
    for k, joint in enumerate(ideal.drives):
        A[:, :, na + k] = 0.0
        A[:, mech.v_index(joint), na + k] = 1.0
    A[:, :, ne:] = np.swapaxes(rows, 1, 2)
    cut_points = full.cut_points(G)
    eye = np.broadcast_to(np.eye(full.size), (n, full.size, full.size))
    loads = full.joint_loads(W[:, None], eye, t[:, None, 1:], cut_points[:, None])  # (N, rows, n_joints, 6)
    reaction_map = np.zeros((n, loads.shape[2], 6, m))
    reaction_map[..., ne:] = loads.transpose(0, 2, 3, 1)
    points = np.concatenate([t[:, 1:], cut_points], axis=1)
    return Pose(Q, R, t, J, points, A, reaction_map, _null_spaces(A), ideal.compliances(R, t, points), ne)


def _null_spaces(A: np.ndarray) -> np.ndarray:
    """(N, m, s) orthonormal null-space bases of A (N, nv, m), zero-padded to the largest.

    Where every sample's A has full row rank (the equilibrium of a regular pose), the last m - nv
    columns of the complete QR of A^T (a third of an SVD's cost); the rank is judged on R's diagonal
    against `core.RANK_TOL`, and a sample that fails it gets the SVD.
    """
    _, nv, m = A.shape
    if nv < m:
        Q, R = np.linalg.qr(np.swapaxes(A, 1, 2), mode="complete")
        d = np.abs(np.diagonal(R[:, :nv], axis1=1, axis2=2))
        full = d.min(axis=1) > 10 * core.RANK_TOL * np.maximum(d.max(axis=1), 1e-290)
        if full.all():
            return Q[:, :, nv:]
    _, s, Vt = np.linalg.svd(A, full_matrices=True)
    rank = np.sum(s > core.RANK_TOL * np.maximum(s[:, :1], 1e-290), axis=1)
    first = int(rank.min()) if len(rank) else m
    keep = np.arange(first, m)[None, :] >= rank[:, None]
    return np.where(keep[..., None], Vt[:, first:], 0.0).transpose(0, 2, 1)


def particular(pose: Pose, b: np.ndarray) -> np.ndarray:
    """The minimum-norm solutions x_p of A x = b.

    Args:
        pose: the rigid statics (its A).
        b: (N, nv, k) right-hand sides (generalised forces, N m or N).

    Returns:
        (N, m, k) x_p.

    Raises:
        SingularConfiguration: a load the locked mechanism cannot hold (it still moves under it).
    """
    x = (
        np.linalg.lstsq(pose.A[0], b[0], rcond=None)[0][None]
        if len(b) == 1
        else np.linalg.pinv(pose.A, rcond=core.RANK_TOL) @ b
    )
    residual = np.linalg.norm(pose.A @ x - b, axis=1)
    scale = np.maximum(np.linalg.norm(b, axis=1), 1e-300)
    if np.any(residual > HELD_TOL * scale):
        raise SingularConfiguration(
            float("inf"),
            "with its actuators locked the mechanism still moves under this load "
            "(an unactuated freedom no joint spring holds): no static answer",
        )
    return x


@dataclass(frozen=True)
class Compatible:
    """The compatible reactions and efforts of N samples and k load cases.

    Attributes:
        reactions: (N, n_joints, 6, k) reactions [f, m], world axes.
        efforts: (N, ne, k) efforts (actuators, then spring drives).
        determinate: (N, n_joints, 6) components fixed by equilibrium and compatibility together.
        rigid_determinate: (N, n_joints, 6) components fixed by equilibrium alone.
    """

    reactions: np.ndarray
    efforts: np.ndarray
    determinate: np.ndarray
    rigid_determinate: np.ndarray


def _variation(Y: np.ndarray) -> np.ndarray:
    """(N, n_joints, 6) norm of each reaction component over the columns of Y (N, n_joints, 6, s)."""
    return np.sqrt(np.square(Y).sum(axis=-1))


def energy_product(
    pose: Pose, drive_compliance: np.ndarray, A: np.ndarray, a: np.ndarray, B: np.ndarray, b: np.ndarray
) -> np.ndarray:
    """The complementary-energy product sum_j A_j^T F_j B_j + a^T diag(c) b of two sets of reactions.

    Args:
        pose: the rigid statics (its joint compliances F_j).
        drive_compliance: (ne,) the effort columns' compliances c (rad/(N m) or m/N; 0: locked).
        A: (N, n_joints, 6, s) the first set's reactions.
        a: (N, ne, s) its efforts.
        B: (N, n_joints, 6, t) the second set's reactions.
        b: (N, ne, t) its efforts.

    Returns:
        (N, s, t) the products (J per unit of each column).
    """
    n, rows = len(A), A.shape[1] * 6
    FB = (pose.compliance @ B).reshape(n, rows, B.shape[-1])
    return (
        np.swapaxes(A.reshape(n, rows, A.shape[-1]), 1, 2) @ FB + np.swapaxes(a * drive_compliance[:, None], 1, 2) @ b
    )


def compatible(pose: Pose, drive_compliance: np.ndarray, reactions: np.ndarray, efforts: np.ndarray) -> Compatible:
    """The compatible equilibrium nearest a given one, moved along the self-stresses to the least
    complementary energy.

    Args:
        pose: the rigid statics (self-stresses, compliances).
        drive_compliance: (ne,) the effort columns' compliances (rad/(N m) or m/N; 0: locked).
        reactions: (N, n_joints, 6, k) the equilibrium's reactions, world axes.
        efforts: (N, ne, k) its efforts.

    Returns:
        The `Compatible` reactions and efforts, with the components they fix.
    """
    ne = len(drive_compliance)
    YR = pose.reaction_map @ pose.null[:, None]  # (N, n_joints, 6, s)
    Yu = pose.null[:, :ne]
    H = energy_product(pose, drive_compliance, YR, Yu, YR, Yu)
    g = energy_product(pose, drive_compliance, YR, Yu, reactions, efforts)
    w, V = np.linalg.eigh(H)
    strained = w > STRAIN_TOL * np.maximum(w[:, -1:], 1e-300)
    inverse = np.where(strained, 1.0 / np.where(strained, w, 1.0), 0.0)
    z = -(V * inverse[:, None, :]) @ np.swapaxes(V, 1, 2) @ g
    free_rigid = _variation(YR)
    free = _variation(YR @ (V * ~strained[:, None, :])[:, None])
    limit = 1e-8 * np.maximum(free_rigid.max(axis=(1, 2), keepdims=True), 1e-300)
    return Compatible(reactions + YR @ z[:, None], efforts + Yu @ z, free <= limit, free_rigid <= limit)


def _unit_wrenches(x: np.ndarray) -> np.ndarray:
    """(..., 6, 6) [[I, 0], [x^, I]]: columns the unit wrenches at points x (..., 3) about the origin
    (a unit force e at x has the moment x cross e there)."""
    out = np.zeros(x.shape[:-1] + (6, 6))
    out[..., range(6), range(6)] = 1.0
    out[..., 3, 1], out[..., 3, 2], out[..., 4, 2] = -x[..., 2], x[..., 1], -x[..., 0]
    out[..., 4, 0], out[..., 5, 0], out[..., 5, 1] = x[..., 2], -x[..., 1], x[..., 0]
    return out


def unit_loads(model: pin.Model, pose: Pose, bodies: np.ndarray, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Six unit wrenches (world axes) at each of some bodies' points: the right-hand sides and the tree
    reactions they cause before any closure acts.

    Args:
        model: the Pinocchio model.
        pose: the rigid statics of the N poses.
        bodies: (k,) Pinocchio ids of the loaded bodies.
        points: (N, k, 3) where they are loaded (world, m).

    Returns:
        b (N, nv, 6k) = -J^T w (the generalised force the joints must balance) and R0 (N, n_joints, 6, 6k):
        every tree joint between the ground and a loaded body carries -w about its origin.
    """
    n, k, nt = len(pose.q), len(bodies), model.njoints - 1
    path = np.zeros((k, nt), dtype=bool)  # tree joints between the ground and each body
    mask = np.zeros((k, model.nv))  # their velocity columns
    for c, body in enumerate(bodies):
        j = int(body)
        while j > 0:
            path[c, j - 1] = True
            mask[c, model.joints[j].idx_v : model.joints[j].idx_v + model.joints[j].nv] = 1.0
            j = model.parents[j]
    W = _unit_wrenches(points)  # (N, k, 6, 6) columns: the unit wrenches at x, about the world origin
    b = -np.einsum("nav,kv,nkaw->nvkw", pose.J, mask, W).reshape(n, model.nv, 6 * k)
    at_joints = _unit_wrenches(points[:, None] - pose.t[:, 1:, None])  # (N, nt, k, 6, 6) about each joint origin
    R0 = np.zeros((n, pose.points.shape[1], 6, k, 6))
    R0[:, :nt] = -np.swapaxes(at_joints * path.T[None, :, :, None, None], 2, 3)
    return b, R0.reshape(n, -1, 6, 6 * k)
