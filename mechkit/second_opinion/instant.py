"""One instant of a mechanism for the second opinion: every body's motion and every joint's point and
wrench directions, from Pinocchio KINEMATICS only (`forwardKinematics`, joint Jacobians, frame
placements; no mass matrix, no RNEA).

World axes throughout. A body's equilibrium rows are its force and its moment about its own joint
origin ``origin``; a joint's wrench directions have their moment about the joint point.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.base.spatial import cross
from mechkit.second_opinion.structure_graph import Cuts, Structure, constraint_span, cut_wrenches, tree_motion


@dataclass(frozen=True)
class BodyMotion:
    """A body at one instant (world): origin and COM (m), mass (kg), inertia about the COM (kg m^2),
    angular velocity (rad/s) and acceleration (rad/s^2), COM acceleration (m/s^2)."""

    origin: np.ndarray
    com: np.ndarray
    mass: float
    inertia: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    com_acceleration: np.ndarray


@dataclass(frozen=True)
class JointGeometry:
    """A joint at one instant: its point (m), the (6, k) world wrench directions of its reaction
    components (moment about the point), and the (6,) wrench of a unit effort (None if passive)."""

    point: np.ndarray
    basis: np.ndarray
    effort: np.ndarray | None


@dataclass(frozen=True)
class Instant:
    """Bodies (id -> motion) and joints (name -> geometry) of one state; gravity (3,) m/s^2; the
    wrenches (6,) the joint springs and dampers transmit, parent side on child side (world, about the
    joint point), by joint."""

    bodies: dict[int, BodyMotion]
    joints: dict[str, JointGeometry]
    gravity: np.ndarray
    passive: dict[str, np.ndarray]


def joint_geometry(model: pin.Model, data: pin.Data, cuts: Cuts, structure: Structure) -> dict[str, JointGeometry]:
    """Every joint's point and wrench directions (world); joint Jacobians and frame placements must be
    current.

    Args:
        model: the tree's Pinocchio model.
        data: its data, kinematics current.
        cuts: the cut joints' full spatial rows (`cut_wrenches`).
        structure: the structure graph.

    Returns:
        Joint -> its point (m), wrench basis (6, components) and effort direction (6,) or None.
    """
    out = {}
    eye = np.eye(6)
    for joint in structure.joints:
        span = constraint_span(model, data, cuts, joint)
        basis = span @ (span.T @ eye[:, list(joint.components)])
        effort = None
        if joint.cut:
            point = data.oMf[cuts.kernel.cuts[joint.index].frame_b].translation.copy()
        else:
            point = data.oMi[joint.index].translation.copy()
            if joint.actuated:
                s = tree_motion(model, data, joint.index)[:, 0]
                effort = s / (s @ s)
        out[joint.name] = JointGeometry(point, basis, effort)
    return out


def instant(
    cm: core.ClosureModel,
    cd: core.ClosureData,
    data: pin.Data,
    structure: Structure,
    q: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    passive: np.ndarray | None = None,
) -> Instant:
    """The instant (q, v, a) (rad, m; rad/s, m/s; rad/s^2, m/s^2) of a mechanism's tree.

    Args:
        cm: the closure model (its full spatial rows are the cut joints of ``structure``).
        cd: a data of it.
        data: a Pinocchio data of the tree (scratch).
        structure: the structure graph.
        q: configuration (nq,).
        v: velocity (nv,).
        a: acceleration (nv,).
        passive: (nv,) generalised forces of the joint springs and dampers (N m or N), or None: each joint's share
            tau_j becomes the wrench w = S (S^T S)^-1 tau_j along its motion subspace S.

    Returns:
        Every body's motion and every joint's geometry (world), gravity, and the passive joints' wrenches.
    """
    model = cm.model
    cuts = cut_wrenches(cm, cd, q)
    pin.computeJointJacobians(model, data, q)
    pin.forwardKinematics(model, data, q, v, a)
    pin.updateFramePlacements(model, data)
    bodies = {}
    for j in structure.bodies:
        placement, inertia = data.oMi[j], model.inertias[j]
        rot = placement.rotation
        vel, acc = data.v[j], data.a[j]
        omega, v_origin = rot @ vel.angular, rot @ vel.linear
        alpha = rot @ acc.angular
        a_origin = rot @ acc.linear + cross(omega, v_origin)
        lever = rot @ inertia.lever
        a_com = a_origin + cross(alpha, lever) + cross(omega, cross(omega, lever))
        bodies[j] = BodyMotion(
            placement.translation.copy(),
            placement.translation + lever,
            float(inertia.mass),
            rot @ inertia.inertia @ rot.T,
            omega,
            alpha,
            a_com,
        )
    loads = {}
    if passive is not None:
        for j in range(1, model.njoints):
            jm = model.joints[j]
            share = passive[jm.idx_v : jm.idx_v + jm.nv]
            if np.any(share != 0.0):
                S = tree_motion(model, data, j)
                loads[model.names[j]] = S @ np.linalg.solve(S.T @ S, share)
    return Instant(bodies, joint_geometry(model, data, cuts, structure), model.gravity.linear.copy(), loads)
