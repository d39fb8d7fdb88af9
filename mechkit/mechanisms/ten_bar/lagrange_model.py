"""The patent's Lagrange first-kind model of the ten-bar from the parameters, and the numpy tree kinematics.

The Lagrange coordinates are the reference-point coordinates of the 9 moving links (COM x, z and the
absolute angle, in `geometry.BODIES` order); `TreeKinematics` maps the URDF's tree-joint angles and
rates to them, `joint_angles_from_lagrange` maps back (numpy only, no Pinocchio).
"""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar.params import MOTORS, TenBarParams, spring
from mechkit.validation import lagrange


def lagrange_linkage(p: TenBarParams, spring_: lagrange.Spring | None = None) -> lagrange.Linkage:
    """The patent's Lagrange first-kind model of the ten-bar, from the parameters (numpy only).

    Args:
        p: the ten-bar's parameters.
        spring_: the R5 spring (default: the parameters').

    Returns:
        The linkage.
    """
    props = geo.mass_properties(p)
    index = {b: i for i, b in enumerate(geo.BODIES)}
    bodies = [lagrange.Body(b, props[b][0], props[b][2], props[b][1]) for b in geo.BODIES]
    pins = [
        lagrange.Pin(
            h.name,
            None if h.parent is None else index[h.parent],
            h.parent_point,
            index[h.child],
            h.child_point,
        )
        for h in geo.hinges(p)
    ]
    return lagrange.Linkage(bodies, pins, MOTORS, (spring_ or spring(p),))


def lagrange_coordinates(p: TenBarParams, pose: geo.Pose) -> np.ndarray:
    """Reference-point coordinates (COM x, z, absolute angle per link) of a closed-form pose.

    Args:
        p: the ten-bar's parameters.
        pose: a closed-form pose.

    Returns:
        (3 * 9,) coordinates: x, z (m), phi (rad) per link.
    """
    props = geo.mass_properties(p)
    h = geo.hinge_points(p)
    q = np.empty(3 * len(geo.BODIES))
    for i, body in enumerate(geo.BODIES):
        phi = pose.angles[body]
        origin_hinge = next(iter(h[body]))  # each body frame's origin is its first hinge
        q[3 * i : 3 * i + 2] = pose.points[origin_hinge] + geo.rot(phi) @ props[body][1]
        q[3 * i + 2] = phi
    return q


class TreeKinematics:
    """Numpy forward kinematics of the spanning tree: joint angles -> reference-point coordinates.

    Joints in `geometry.TREE_JOINTS` order; the rates may be a (9,) vector or a (9, k) matrix (k rate
    vectors at once: with the identity, the columns of d q_L / d theta).
    """

    def __init__(self, p: TenBarParams):
        props = geo.mass_properties(p)
        index = {b: i for i, b in enumerate(geo.BODIES)}
        self.steps = [
            (None if h.parent is None else index[h.parent], h.parent_point, index[h.child])
            for h in geo.hinges(p)[: len(geo.TREE_JOINTS)]
        ]
        self.coms = [props[b][1] for b in geo.BODIES]

    def __call__(self, angles: np.ndarray, rates: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(q_L (27,), qd_L (27,) or (27, k)) from tree-joint angles and rates (rad, rad/s)."""
        rates = np.asarray(rates, dtype=float)
        shape = rates.shape[1:]
        n = len(self.coms)
        origin, origin_rate = np.zeros((n, 2)), np.zeros((n, 2) + shape)
        phi, omega = np.zeros(n), np.zeros((n,) + shape)
        for k, (parent, point, child) in enumerate(self.steps):
            if parent is None:
                arm, o, od, ph, w = point, np.zeros(2), np.zeros((2,) + shape), 0.0, np.zeros(shape)
            else:
                ph, w = phi[parent], omega[parent]
                arm = geo.rot(ph) @ point
                o, od = origin[parent], origin_rate[parent]
            origin[child] = o + arm
            origin_rate[child] = od + np.multiply.outer([-arm[1], arm[0]], w)
            phi[child] = ph + angles[k]
            omega[child] = w + rates[k]
        q, qd = np.empty(3 * n), np.empty((3 * n,) + shape)
        for i, com in enumerate(self.coms):
            c = geo.rot(phi[i]) @ com
            q[3 * i : 3 * i + 3] = [*(origin[i] + c), phi[i]]
            qd[3 * i : 3 * i + 2] = origin_rate[i] + np.multiply.outer([-c[1], c[0]], omega[i])
            qd[3 * i + 2] = omega[i]
        return q, qd


def lagrange_from_joints(
    p: TenBarParams, angles: dict[str, float], rates: dict[str, float]
) -> tuple[np.ndarray, np.ndarray]:
    """Reference-point coordinates and rates from tree-joint angles and rates (numpy forward kinematics).

    Args:
        p: the ten-bar's parameters.
        angles: tree joint -> angle (rad).
        rates: tree joint -> rate (rad/s).

    Returns:
        (q_L, qd_L), 3 per link.
    """
    fk = TreeKinematics(p)
    return fk(np.array([angles[j] for j in geo.TREE_JOINTS]), np.array([rates[j] for j in geo.TREE_JOINTS]))


def joint_angles_from_lagrange(q: np.ndarray) -> dict[str, float]:
    """URDF tree-joint values from reference-point coordinates (relative absolute angles, rad).

    Args:
        q: reference-point coordinates (3 per link).

    Returns:
        Tree joint -> value (rad).
    """
    return geo.relative_angles({b: q[3 * i + 2] for i, b in enumerate(geo.BODIES)})
