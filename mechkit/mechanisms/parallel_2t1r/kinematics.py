"""The 2T1R parallel mechanism's own analytic position kinematics (Huang, Shen, Li, Zhu, Yang), numpy only.

Geometry (paper section 2.1, base frame {o}: x along A2A1, z up, every joint axis along y):
A1 = (l1/2, l1/2, 0), A2 = (-l1/2, l1/2, 0), A3 = (-l1/2, -l1/2, 0), A4 = (l1/2, -l1/2, 0);
proximal links A_d B_d of length l2 make the angle theta_d with the -x axis,
B_d = A_d + l2 (-cos theta_d, 0, sin theta_d); distal links B_d C_d have length l2. The platform pose
is (x_p, z_p, alpha), alpha a rotation about +y; its hinge points are C1 = (x_p, l1/2, z_p) (the
compound hinge R13/R23, C2 = C1), C3 = p - (l3/2) u and C4 = p + (l3/2) u with
u = (cos alpha, 0, -sin alpha). Limb I (A1-B1-C1-B2-A2) is a five-bar; limbs II (A3-B3-C3) and
III (A4-B4-C4) are RRR chains; theta_4 (limb III) is a follower unless limb III is driven.

Every angle is a rotation about +y (right hand): a body at absolute angle phi has its local x axis
along (cos phi, 0, -sin phi); proximal link d is at phi = pi + theta_d.

Forward kinematics (eqs. (7)-(9)), inverse kinematics (eq. (10)) and the closure of each limb;
velocities and accelerations are in `rates`. Departure from the printed paper, checked by a test:
eq. (7) solves the two circles through a linear relation z = a x + b that divides by z_B2 - z_B1
(zero on the motion law's start); we intersect the circles with the equivalent
midpoint-perpendicular form (same two roots).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidParameters

__all__ = [
    "BODIES",
    "DOUBLE_ROOT",
    "EY",
    "Dims",
    "FKSolution",
    "Pose",
    "alpha_discriminant",
    "base_points",
    "direction",
    "distal_angles",
    "elbow_points",
    "end_points",
    "five_bar_discriminant",
    "follower_angles",
    "forward_kinematics",
    "inverse_kinematics",
    "loop_residuals",
    "platform_points",
    "solve_trig",
]

#: Unit vector of every joint axis (base frame).
EY = np.array([0.0, 1.0, 0.0])
#: Moving bodies, named as the URDF links: link<d>1 = A_d B_d, link<d>2 = B_d C_d.
BODIES = ("link11", "link12", "link21", "link22", "link31", "link32", "link41", "link42", "platform")
#: Relative discriminant below which two roots count as one (a double root: a singular pose).
DOUBLE_ROOT = 1e-12


@dataclass(frozen=True)
class Dims:
    """Dimensions (m): base square side l1, link length l2, platform side C3C4 = l3."""

    l1: float
    l2: float
    l3: float


@dataclass(frozen=True)
class Pose:
    """Platform pose: centroid p = (x, z) (m, base frame) and attitude alpha about +y (rad)."""

    x: float
    z: float
    alpha: float

    def array(self) -> np.ndarray:
        """(x (m), z (m), alpha (rad)) as an array (3,)."""
        return np.array([self.x, self.z, self.alpha])


def direction(angle: float) -> np.ndarray:
    """Unit x axis (3,) of a body at absolute angle ``angle`` (rad) about +y.

    Args:
        angle: the body's absolute angle about +y, rad.

    Returns:
        (3,) unit vector.
    """
    return np.array([np.cos(angle), 0.0, -np.sin(angle)])


def _wrap(a: float) -> float:
    return float((a + np.pi) % (2.0 * np.pi) - np.pi)


def solve_trig(a: float, b: float, c: float, name: str) -> tuple[tuple[float, float], float]:
    """Both roots of ``a sin x + b cos x + c = 0`` (the paper's form of eqs. (8), (9), (10)).

    Args:
        a: coefficient of sin x.
        b: coefficient of cos x.
        c: constant term.
        name: the unknown's name, for the error.

    Returns:
        ((x_plus, x_minus) in (-pi, pi], relative discriminant (a^2 + b^2 - c^2) / (a^2 + b^2)).
        A relative discriminant below ``DOUBLE_ROOT`` marks a double root (a singular pose).

    Raises:
        InvalidParameters: no real root (the limb cannot reach).
    """
    rho2 = a * a + b * b
    disc = (rho2 - c * c) / rho2 if rho2 > 0.0 else -1.0
    if disc < -DOUBLE_ROOT:
        raise InvalidParameters(name, (a, b, c), f"out of reach: relative discriminant {disc:.3e} < 0")
    phase, half = np.arctan2(a, b), np.arctan2(np.sqrt(max(disc, 0.0) * rho2), -c)
    return (_wrap(phase + half), _wrap(phase - half)), disc


def base_points(d: Dims) -> np.ndarray:
    """A1..A4 (4, 3), m, base frame.

    Args:
        d: the mechanism's dimensions (m).

    Returns:
        (4, 3) points, m.
    """
    h = d.l1 / 2.0
    return np.array([[h, h, 0.0], [-h, h, 0.0], [-h, -h, 0.0], [h, -h, 0.0]])


def elbow_points(d: Dims, theta: np.ndarray) -> np.ndarray:
    """B_d = A_d + l2 (-cos theta_d, 0, sin theta_d) for the given proximal angles (k, 3), m.

    Args:
        d: the mechanism's dimensions (m).
        theta: proximal angles (k,), rad, of limbs 1..k.

    Returns:
        (k, 3) points, m.
    """
    theta = np.asarray(theta, dtype=float)
    out = base_points(d)[: theta.size]
    out[:, 0] -= d.l2 * np.cos(theta)
    out[:, 2] += d.l2 * np.sin(theta)
    return out


def platform_points(d: Dims, pose: Pose) -> dict[str, np.ndarray]:
    """Platform points (3,) m, base frame: centroid p, hinges C1 (= C2), C3, C4.

    C1 lies in limb I's plane y = l1/2, C3 and C4 in y = -l1/2, p at their centroid y = -l1/6.

    Args:
        d: the mechanism's dimensions (m).
        pose: a platform pose (x, z in m, alpha in rad).

    Returns:
        Name ("p", "C1", "C3", "C4") -> point (3,), m.
    """
    u = direction(pose.alpha)
    h = d.l1 / 2.0
    p = np.array([pose.x, -d.l1 / 6.0, pose.z])
    c3 = p - 0.5 * d.l3 * u
    c4 = p + 0.5 * d.l3 * u
    c3[1] = c4[1] = -h
    return {"p": p, "C1": np.array([pose.x, h, pose.z]), "C3": c3, "C4": c4}


def end_points(d: Dims, pose: Pose) -> np.ndarray:
    """C1, C1, C3, C4 (4, 3): the distal end of limb d = 1..4.

    Args:
        d: the mechanism's dimensions (m).
        pose: a platform pose (x, z in m, alpha in rad).

    Returns:
        (4, 3) points, m.
    """
    c = platform_points(d, pose)
    return np.array([c["C1"], c["C1"], c["C3"], c["C4"]])


def _proximal_roots(d: Dims, a: np.ndarray, c: np.ndarray, name: str) -> tuple[tuple[float, float], float]:
    """Both proximal angles of an RR dyad from base A to end C (eqs. (9), (10))."""
    dx, dz = c[0] - a[0], c[2] - a[2]
    return solve_trig(-2.0 * d.l2 * dz, 2.0 * d.l2 * dx, dx * dx + dz * dz, name)


@dataclass(frozen=True)
class FKSolution:
    """One forward-kinematics solution: pose, branch (C1 root, alpha root) in {0, 1}^2, and the
    smaller relative discriminant of its two root pairs (below ``DOUBLE_ROOT``: a singular pose)."""

    pose: Pose
    branch: tuple[int, int]
    discriminant: float


def forward_kinematics(d: Dims, theta: np.ndarray) -> list[FKSolution]:
    """All real platform poses for the inputs theta_1..theta_3 (rad): eqs. (7)-(8), up to 4.

    C1 root 0 puts C1 on the side of B1B2 reached by turning B1->B2 by -90 deg about y (above the
    chord when B2 lies at -x of B1), root 1 on the other side; alpha roots as in `solve_trig`.
    A C1 for which limb II cannot reach C3 contributes no pose.

    Args:
        d: the mechanism's dimensions (m).
        theta: the inputs theta_1..theta_3 (3,), rad.

    Returns:
        The solutions: pose, root labels (C1 root, alpha root) and the discriminants.

    Raises:
        InvalidParameters: no pose at all (limb I cannot close, or limb II reaches no C3).
    """
    theta = np.asarray(theta, dtype=float)
    if theta.shape != (3,) or not np.all(np.isfinite(theta)):
        raise InvalidParameters("theta", theta, "need 3 finite input angles (rad)")
    b = elbow_points(d, np.append(theta, 0.0))
    chord = b[1] - b[0]
    dist2 = float(chord @ chord)
    disc1 = five_bar_discriminant(d, theta)
    if disc1 < -DOUBLE_ROOT:
        raise InvalidParameters("theta", theta, f"B1B2 = {np.sqrt(dist2):.6g} m > 2 l2: limb I cannot close")
    normal = np.array([chord[2], 0.0, -chord[0]]) / np.sqrt(dist2)
    height = d.l2 * np.sqrt(max(disc1, 0.0))
    poses = []
    for i, s in enumerate((1.0, -1.0)):
        c1 = 0.5 * (b[0] + b[1]) + s * height * normal
        try:
            roots, disc2 = solve_trig(*_alpha_coefficients(d, c1, theta[2]), "theta3")
        except InvalidParameters:
            continue
        poses += [
            FKSolution(Pose(float(c1[0]), float(c1[2]), alpha), (i, j), min(disc1, disc2))
            for j, alpha in enumerate(roots)
        ]
    if not poses:
        raise InvalidParameters("theta", theta, "limb II cannot reach the platform for either C1")
    return poses


def five_bar_discriminant(d: Dims, theta: np.ndarray) -> float:
    """1 - (B1B2 / 2 l2)^2 for the inputs theta_1, theta_2: zero when the five-bar's distal links are
    collinear (C1 a double root of eq. (7), a parallel singularity), negative when it cannot close.

    Args:
        d: the mechanism's dimensions (m).
        theta: theta_1, theta_2 (at least 2), rad.

    Returns:
        The discriminant (-).
    """
    b = elbow_points(d, np.append(np.asarray(theta, dtype=float)[:2], 0.0))[:2]
    chord = b[1] - b[0]
    return float(1.0 - (chord @ chord) / (4.0 * d.l2**2))


def _alpha_coefficients(d: Dims, c1: np.ndarray, theta3: float) -> tuple[float, float, float]:
    """A, B, C of eq. (8), A sin alpha + B cos alpha + C = 0 (scaled by l3), for C1 and theta_3."""
    r = c1[0] + d.l1 / 2.0 + d.l2 * np.cos(theta3)
    sz = c1[2] - d.l2 * np.sin(theta3)
    return sz, -r, (r * r + sz * sz + d.l3**2 / 4.0 - d.l2**2) / d.l3


def alpha_discriminant(d: Dims, theta: np.ndarray, pose: Pose) -> float:
    """Relative discriminant of eq. (8) at the inputs theta and the C1 of ``pose``: zero when limb II's
    distal link B3C3 points at the platform centre p (a parallel singularity), negative beyond.

    Args:
        d: the mechanism's dimensions (m).
        theta: the inputs theta_1..theta_3 (3,), rad.
        pose: a platform pose (x, z in m, alpha in rad).

    Returns:
        The relative discriminant (-).
    """
    a, b, c = _alpha_coefficients(d, np.array([pose.x, 0.0, pose.z]), float(theta[2]))
    return float((a * a + b * b - c * c) / (a * a + b * b))


def follower_angles(d: Dims, pose: Pose) -> tuple[tuple[float, float], float]:
    """Both follower angles theta_4 of limb III for a platform pose (eq. (9)), and the discriminant.

    Args:
        d: the mechanism's dimensions (m).
        pose: a platform pose (x, z in m, alpha in rad).

    Returns:
        ((both roots of theta_4, rad), the discriminant (-)).

    Raises:
        InvalidParameters: limb III cannot reach the pose.
    """
    return _proximal_roots(d, base_points(d)[3], platform_points(d, pose)["C4"], "theta4")


def inverse_kinematics(d: Dims, pose: Pose) -> np.ndarray:
    """All 8 input sets (theta_1, theta_2, theta_3) (rad) for a platform pose: eq. (10).

    Row k holds the roots (k >> 2 & 1, k >> 1 & 1, k & 1) of theta_1, theta_2, theta_3 (0 = the
    ``+`` root of ``solve_trig``). With the 2 follower roots of theta_4, 16 configurations.

    Args:
        d: the mechanism's dimensions (m).
        pose: a platform pose (x, z in m, alpha in rad).

    Returns:
        (8, 3) input sets, rad.

    Raises:
        InvalidParameters: a limb cannot reach the pose.
    """
    a, c = base_points(d), end_points(d, pose)
    roots = [_proximal_roots(d, a[i], c[i], f"theta{i + 1}")[0] for i in range(3)]
    return np.array(list(itertools.product(*roots)))


def distal_angles(d: Dims, theta: np.ndarray, pose: Pose) -> np.ndarray:
    """Absolute angles (4,) rad of the distal links B_d C_d (direction (C_d - B_d) / l2).

    Args:
        d: the mechanism's dimensions (m).
        theta: theta_1..theta_4 (4,), rad.
        pose: a platform pose (x, z in m, alpha in rad).

    Returns:
        (4,) angles, rad.
    """
    r = end_points(d, pose) - elbow_points(d, theta)
    return np.arctan2(-r[:, 2], r[:, 0])


def loop_residuals(d: Dims, theta: np.ndarray, pose: Pose) -> np.ndarray:
    """|C_d - B_d| - l2 (4,) m for theta_1..theta_4: zero when every limb closes.

    Args:
        d: the mechanism's dimensions (m).
        theta: theta_1..theta_4 (4,), rad.
        pose: a platform pose (x, z in m, alpha in rad).

    Returns:
        (4,) residuals, m.
    """
    r = end_points(d, pose) - elbow_points(d, theta)
    return np.hypot(r[:, 0], r[:, 2]) - d.l2
