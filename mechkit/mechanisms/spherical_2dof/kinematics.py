"""The paper's own kinematics of the 2-DOF spherical platform (Zhang et al. 2016), numpy only.

Frames (all origins at the motion centre O, the Hooke-joint centre): base frame O-X0Y0Z0 with Z0
along the strut towards the platform (up) and X0 = Z0 x Z11 / |Z0 x Z11|; platform frame O-XYZ with
Z normal to the platform and X = Z x Z13 / |Z x Z13|. Unit axes: u_i of the base joint (motor) of limb
i, w_i of its middle joint, v_i of its platform joint, all pointing out of the sphere.

Conventions that the source leaves out (ours, derived in docs/mechanisms/spherical_2dof.md):

- Attitude ``phi = (phi_x, phi_y)`` (roll, pitch) of the Hooke joint: outer axis X0 fixed to the
  strut, inner axis the platform's Y; ``R = Rx(phi_x) Ry(phi_y)``, platform normal ``n = R e_z``.
- Platform-side axes mirror eq. (5) with their own cone angle ``beta_platform`` (b'):
  ``v_i = R [s(eta2i) s(b'), -c(eta2i) s(b'), -c(b')]``; the default b' = 90 deg puts them in the
  platform plane (b' = beta would make u_i = v_i at home, which cannot assemble).

Limb i as a serial chain: ``F_i0 = Rz(eta1i) Rx(pi - beta)`` (z = u_i, eq. 5); link i1 is
``F_i0 Rz(theta_i1)``; the middle axis is ``w_i = F_i0 Rz(theta_i1) Rx(-alpha1) e_z`` (third column of
eq. 4, term by term); link i2 is ``F_i0 Rz(theta_i1) Rx(-alpha1) Rz(theta_i2)`` and its distal axis
``Rx(-alpha2) e_z`` in link i2 must equal v_i: the constraint ``w_i . v_i = cos(alpha2)`` (eq. 7).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

import numpy as np

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.base.spatial import cross, rot_x, rot_y, rot_z

__all__ = [
    "BRANCHES",
    "Geometry",
    "base_axis",
    "base_frame",
    "condition",
    "constraint",
    "constraint_jacobians",
    "cross",
    "hooke_rates",
    "ik_coefficients",
    "inverse_kinematics",
    "jacobian",
    "limb_angles",
    "limb_rates",
    "middle_axis",
    "platform_axis",
    "platform_normal",
    "platform_rotation",
    "rot_x",
    "rot_y",
    "rot_z",
]

#: Assembly branch (+1 / -1 per limb, see `inverse_kinematics`) used for the home pose and every scene (ours).
BRANCHES = (1, 1)


class Geometry(Protocol):
    """The structural parameters (rad) the kinematics needs; `Spherical2DofParams` provides them."""

    alpha1: float
    alpha2: float
    beta: float
    beta_platform: float
    eta11: float
    eta12: float
    eta21: float
    eta22: float


def _etas(p: Geometry, i: int) -> tuple[float, float]:
    """(eta1i, eta2i) of limb ``i`` (1 or 2): the base and platform azimuths, rad."""
    if i not in (1, 2):
        raise InvalidParameters("limb", i, "limbs are numbered 1 and 2")
    return (p.eta11, p.eta21) if i == 1 else (p.eta12, p.eta22)


def platform_rotation(phi: Sequence[float]) -> np.ndarray:
    """Platform attitude ``R = Rx(phi_x) Ry(phi_y)`` (platform frame -> base frame).

    Args:
        phi: attitude (roll, pitch), rad.

    Returns:
        (3, 3) rotation matrix.
    """
    return rot_x(phi[0]) @ rot_y(phi[1])


def platform_normal(phi: np.ndarray) -> np.ndarray:
    """Unit platform normal n = R(phi) e_z (base frame) of attitudes (..., 2).

    Args:
        phi: attitudes (..., 2), rad.

    Returns:
        (..., 3) unit normals.
    """
    phi = np.asarray(phi, dtype=float)
    px, py = phi[..., 0], phi[..., 1]
    return np.stack([np.sin(py), -np.sin(px) * np.cos(py), np.cos(px) * np.cos(py)], axis=-1)


def base_frame(p: Geometry, i: int) -> np.ndarray:
    """``F_i0 = Rz(eta1i) Rx(pi - beta)``: frame of limb i's motor joint, z = u_i (base frame).

    Args:
        p: the structural parameters.
        i: the limb, 1 or 2.

    Returns:
        (3, 3) rotation matrix.
    """
    return rot_z(_etas(p, i)[0]) @ rot_x(np.pi - p.beta)


def base_axis(p: Geometry, i: int) -> np.ndarray:
    """u_i (eq. 5): ``[s(eta1i) s(beta), -c(eta1i) s(beta), -c(beta)]``, base frame.

    Args:
        p: the structural parameters.
        i: the limb, 1 or 2.

    Returns:
        (3,) unit axis.
    """
    return base_frame(p, i)[:, 2]


def platform_frame_local(p: Geometry, i: int) -> np.ndarray:
    """``P_i = Rz(eta2i) Rx(pi - b')``: frame of limb i's platform joint in the platform frame, z = v_i.

    Args:
        p: the structural parameters.
        i: the limb, 1 or 2.

    Returns:
        (3, 3) rotation matrix.
    """
    return rot_z(_etas(p, i)[1]) @ rot_x(np.pi - p.beta_platform)


def platform_axis(p: Geometry, i: int, phi: Sequence[float]) -> np.ndarray:
    """v_i (our eq. 6): ``R(phi) [s(eta2i) s(b'), -c(eta2i) s(b'), -c(b')]``, base frame.

    Args:
        p: the structural parameters.
        i: the limb, 1 or 2.
        phi: attitude (roll, pitch), rad.

    Returns:
        (3,) unit axis.
    """
    return platform_rotation(phi) @ platform_frame_local(p, i)[:, 2]


def middle_axis(p: Geometry, i: int, theta1: float) -> np.ndarray:
    """w_i (eq. 4, third column): the middle joint axis of limb i at motor angle ``theta1``.

    Args:
        p: the structural parameters.
        i: the limb, 1 or 2.
        theta1: limb i's motor angle, rad.

    Returns:
        (3,) unit axis, base frame.
    """
    return base_frame(p, i) @ rot_z(theta1) @ rot_x(-p.alpha1)[:, 2]


def ik_coefficients(p: Geometry, i: int, v: np.ndarray) -> tuple[float, float, float]:
    """(A_i, B_i, C_i) of ``A sin(theta_i1) + B cos(theta_i1) + C = 0`` (eq. 7 expanded, as printed).

    Args:
        p: the structural parameters.
        i: the limb, 1 or 2.
        v: the platform axis v_i (3,), base frame.

    Returns:
        (A_i, B_i, C_i).
    """
    eta = _etas(p, i)[0]
    sa1, ca1, sb, cb = np.sin(p.alpha1), np.cos(p.alpha1), np.sin(p.beta), np.cos(p.beta)
    se, ce = np.sin(eta), np.cos(eta)
    a = -sa1 * ce * v[0] - sa1 * se * v[1]
    b = sa1 * se * cb * v[0] - sa1 * ce * cb * v[1] + sb * sa1 * v[2]
    c = se * sb * ca1 * v[0] - ce * sb * ca1 * v[1] - cb * ca1 * v[2] - np.cos(p.alpha2)
    return float(a), float(b), float(c)


def inverse_kinematics(p: Geometry, phi: Sequence[float], branches: Sequence[int] = BRANCHES) -> np.ndarray:
    """Motor angles (theta_11, theta_21) (rad) of attitude ``phi`` (eq. 8).

    Eq. (8) solves ``A s + B c + C = 0``; written as ``r cos(theta - atan2(A, B)) = -C`` with
    ``r = hypot(A, B)`` it gives ``theta = atan2(A, B) + k acos(-C / r)``, k = +1 or -1 the branch
    (the same two roots as the half-angle form ``tan(theta/2) = (A -+ sqrt(A^2+B^2-C^2)) / (B - C)``).

    Args:
        p: structural parameters.
        phi: (roll, pitch), rad.
        branches: per limb, +1 or -1.

    Returns:
        (2,) motor angles, rad, in (-pi, pi].

    Raises:
        InvalidParameters: a limb cannot reach the attitude (|C| > hypot(A, B): the u-v arc leaves
            [|alpha1 - alpha2|, alpha1 + alpha2]), or a branch is not +-1.
    """
    theta = np.empty(2)
    for k, i in enumerate((1, 2)):
        if branches[k] not in (1, -1):
            raise InvalidParameters("branches", tuple(branches), "each branch is +1 or -1")
        a, b, c = ik_coefficients(p, i, platform_axis(p, i, phi))
        r = np.hypot(a, b)
        if not abs(c) <= r:
            why = f"limb {i} cannot reach this attitude (|C| = {abs(c):.3e} > sqrt(A^2+B^2) = {r:.3e})"
            raise InvalidParameters("phi", tuple(float(x) for x in phi), why)
        theta[k] = np.arctan2(a, b) + branches[k] * np.arccos(-c / r)
    return (theta + np.pi) % (2 * np.pi) - np.pi


def constraint(p: Geometry, theta: Sequence[float], phi: Sequence[float]) -> np.ndarray:
    """Residuals ``w_i . v_i - cos(alpha2)`` (2,) of eq. (7).

    Args:
        p: the structural parameters.
        theta: motor angles (2,), rad.
        phi: attitude (roll, pitch), rad.

    Returns:
        (2,) residuals (-).
    """
    return np.array(
        [middle_axis(p, i, theta[k]) @ platform_axis(p, i, phi) - np.cos(p.alpha2) for k, i in enumerate((1, 2))]
    )


def _hooke_axes(phi: Sequence[float]) -> np.ndarray:
    """Columns: the Hooke axes X0 and Rx(phi_x) e_y (base frame): d(rotation)/d(phi) columns."""
    return np.column_stack([[1.0, 0.0, 0.0], rot_x(phi[0])[:, 1]])


def constraint_jacobians(p: Geometry, theta: Sequence[float], phi: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    """The matrices of eq. (10), ``A theta' + B phi' = 0``.

    Args:
        p: the structural parameters.
        theta: motor angles (2,), rad.
        phi: attitude (roll, pitch), rad.

    Returns:
        A (2, 2), diagonal: ``d f_i / d theta_i1 = (u_i x w_i) . v_i``;
        B (2, 2): ``d f_i / d phi_j = w_i . (h_j x v_i)``, h_j the Hooke axes (X0, Rx(phi_x) e_y).
    """
    hooke = _hooke_axes(phi)
    a = np.zeros((2, 2))
    b = np.zeros((2, 2))
    for k, i in enumerate((1, 2)):
        w, v = middle_axis(p, i, theta[k]), platform_axis(p, i, phi)
        a[k, k] = cross(base_axis(p, i), w) @ v
        b[k] = [w @ cross(hooke[:, j], v) for j in range(2)]
    return a, b


def condition(m: np.ndarray) -> float:
    """The 2-norm condition number of a matrix (inf when singular).

    Args:
        m: a square matrix.

    Returns:
        Its largest singular value over its smallest (-).
    """
    sv = np.linalg.svd(m, compute_uv=False)
    return float(sv[0] / sv[-1]) if sv[-1] > 0 else np.inf


def jacobian(p: Geometry, theta: Sequence[float], phi: Sequence[float], max_cond: float = 1e12) -> np.ndarray:
    """``J = -B^-1 A`` (eq. 12): ``phi' = J theta'`` (rad/s per rad/s).

    Args:
        p: the structural parameters.
        theta: motor angles (2,), rad.
        phi: attitude (roll, pitch), rad.
        max_cond: the largest condition number of B accepted.

    Returns:
        J (2, 2).

    Raises:
        SingularConfiguration: B is singular (a forward-kinematics singularity).
    """
    a, b = constraint_jacobians(p, theta, phi)
    cond = condition(b)
    if cond > max_cond:
        raise SingularConfiguration(cond, "matrix B of eq. (10) (forward kinematic singularity)")
    return -np.linalg.solve(b, a)


def limb_angles(p: Geometry, i: int, theta1: float, phi: Sequence[float]) -> tuple[float, float]:
    """(theta_i2, theta_i3) (rad): middle joint and platform joint angles of limb i.

    theta_i2 turns link i2 about w_i so its distal axis is the closest to v_i (equal to it when
    eq. 7 holds); theta_i3 is the rotation about v_i from link i2 to the platform-side frame P_i.

    Args:
        p: the structural parameters.
        i: the limb, 1 or 2.
        theta1: limb i's motor angle, rad.
        phi: attitude (roll, pitch), rad.

    Returns:
        (theta_i2, theta_i3), rad.
    """
    frame = base_frame(p, i) @ rot_z(theta1) @ rot_x(-p.alpha1)
    g = frame.T @ platform_axis(p, i, phi)
    theta2 = float(np.arctan2(-g[0], g[1]))
    link2 = frame @ rot_z(theta2) @ rot_x(-p.alpha2)
    rel = link2.T @ platform_rotation(phi) @ platform_frame_local(p, i)
    return theta2, float(np.arctan2(rel[1, 0], rel[0, 0]))


def hooke_rates(
    phi: Sequence[float], phi_dot: Sequence[float], phi_ddot: Sequence[float]
) -> tuple[np.ndarray, np.ndarray]:
    """Platform angular velocity and acceleration (rad/s, rad/s^2, base frame) from roll/pitch rates.

    Args:
        phi: attitude (roll, pitch), rad.
        phi_dot: its rates, rad/s.
        phi_ddot: its accelerations, rad/s^2.

    Returns:
        (omega (3,), alpha (3,)).
    """
    h = _hooke_axes(phi)
    omega = h @ np.asarray(phi_dot, dtype=float)
    # d/dt of the second axis Rx(phi_x) e_y is (phi_x' e_x) x that axis.
    alpha = h @ np.asarray(phi_ddot, dtype=float) + phi_dot[0] * phi_dot[1] * cross(h[:, 0], h[:, 1])
    return omega, alpha


def limb_rates(
    p: Geometry, i: int, theta1: float, phi: Sequence[float], omega_p: np.ndarray, alpha_p: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Joint rates and accelerations (3,) of limb i's (theta_i1, theta_i2, theta_i3).

    Velocity loop ``theta1' u + theta2' w + theta3' v = omega_p`` and its time derivative
    ``[u w v] theta'' = alpha_p - (theta1' u) x (theta2' w) - (theta1' u + theta2' w) x (theta3' v)``.

    Args:
        p: the structural parameters.
        i: the limb, 1 or 2.
        theta1: limb i's motor angle, rad.
        phi: attitude (roll, pitch), rad.
        omega_p: the platform's angular velocity (3,), rad/s, base frame.
        alpha_p: its angular acceleration (3,), rad/s^2.

    Returns:
        (rates (3,) rad/s, accelerations (3,) rad/s^2).

    Raises:
        SingularConfiguration: u, w, v coplanar (the limb is stretched or folded).
    """
    u, w, v = base_axis(p, i), middle_axis(p, i, theta1), platform_axis(p, i, phi)
    m = np.column_stack([u, w, v])
    cond = condition(m)
    if cond > 1e12:
        raise SingularConfiguration(cond, f"limb {i} axes u, w, v coplanar")
    rate = np.linalg.solve(m, omega_p)
    w1, w2, w3 = rate[0] * u, rate[1] * w, rate[2] * v
    acc = np.linalg.solve(m, alpha_p - cross(w1, w2) - cross(w1 + w2, w3))
    return rate, acc
