"""The 2T1R parallel mechanism's own analytic kinematics (Huang, Shen, Li, Zhu, Yang), numpy only.

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

Departures from the printed paper, each checked by a test:
- eq. (7) solves the two circles through a linear relation z = a x + b that divides by
  z_B2 - z_B1 (zero on the motion law's start); we intersect the circles with the equivalent
  midpoint-perpendicular form (same two roots).
- the printed g_ii of eq. (11) have the opposite sign of the time derivative of the printed
  constraints; we use the derivative (finite differences confirm it), so J_p v = J_q omega holds.
- k_1..k_3 of eq. (15) (lost, "scan the QR code") are derived here: J_p a = J_q eps + dJ_q omega -
  dJ_p v.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from mechkit.spatial import cross

from mechkit.exceptions import InvalidParameters, SingularConfiguration

__all__ = [
    "BODIES",
    "BodyMotion",
    "Dims",
    "FKSolution",
    "Pose",
    "State",
    "alpha_discriminant",
    "base_points",
    "cross",
    "distal_angles",
    "elbow_points",
    "five_bar_discriminant",
    "follower_angles",
    "follower_rate",
    "forward_kinematics",
    "inverse_kinematics",
    "jacobians",
    "link_motion",
    "loop_residuals",
    "motion_state",
    "platform_points",
    "solve_trig",
]

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
        return np.array([self.x, self.z, self.alpha])


def direction(angle: float) -> np.ndarray:
    """Unit x axis (3,) of a body at absolute angle ``angle`` (rad) about +y."""
    return np.array([np.cos(angle), 0.0, -np.sin(angle)])


def _wrap(a: float) -> float:
    return float((a + np.pi) % (2.0 * np.pi) - np.pi)


def solve_trig(a: float, b: float, c: float, name: str) -> tuple[tuple[float, float], float]:
    """Both roots of ``a sin x + b cos x + c = 0`` (the paper's form of eqs. (8), (9), (10)).

    Args:
        a, b, c: coefficients.
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
    """A1..A4 (4, 3), m, base frame."""
    h = d.l1 / 2.0
    return np.array([[h, h, 0.0], [-h, h, 0.0], [-h, -h, 0.0], [h, -h, 0.0]])


def elbow_points(d: Dims, theta: np.ndarray) -> np.ndarray:
    """B_d = A_d + l2 (-cos theta_d, 0, sin theta_d) for the given proximal angles (k, 3), m."""
    theta = np.asarray(theta, dtype=float)
    out = base_points(d)[: theta.size]
    out[:, 0] -= d.l2 * np.cos(theta)
    out[:, 2] += d.l2 * np.sin(theta)
    return out


def platform_points(d: Dims, pose: Pose) -> dict[str, np.ndarray]:
    """Platform points (3,) m, base frame: centroid p, hinges C1 (= C2), C3, C4.

    C1 lies in limb I's plane y = l1/2, C3 and C4 in y = -l1/2, p at their centroid y = -l1/6.
    """
    u = direction(pose.alpha)
    h = d.l1 / 2.0
    p = np.array([pose.x, -d.l1 / 6.0, pose.z])
    c3 = p - 0.5 * d.l3 * u
    c4 = p + 0.5 * d.l3 * u
    c3[1] = c4[1] = -h
    return {"p": p, "C1": np.array([pose.x, h, pose.z]), "C3": c3, "C4": c4}


def _end_points(d: Dims, pose: Pose) -> np.ndarray:
    """C1, C1, C3, C4 (4, 3): the distal end of limb d = 1..4."""
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
        poses += [FKSolution(Pose(float(c1[0]), float(c1[2]), alpha), (i, j), min(disc1, disc2))
                  for j, alpha in enumerate(roots)]
    if not poses:
        raise InvalidParameters("theta", theta, "limb II cannot reach the platform for either C1")
    return poses


def five_bar_discriminant(d: Dims, theta: np.ndarray) -> float:
    """1 - (B1B2 / 2 l2)^2 for the inputs theta_1, theta_2: zero when the five-bar's distal links are
    collinear (C1 a double root of eq. (7), a parallel singularity), negative when it cannot close."""
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
    distal link B3C3 points at the platform centre p (a parallel singularity), negative beyond."""
    a, b, c = _alpha_coefficients(d, np.array([pose.x, 0.0, pose.z]), float(theta[2]))
    return float((a * a + b * b - c * c) / (a * a + b * b))


def follower_angles(d: Dims, pose: Pose) -> tuple[tuple[float, float], float]:
    """Both follower angles theta_4 of limb III for a platform pose (eq. (9)), and the discriminant."""
    return _proximal_roots(d, base_points(d)[3], platform_points(d, pose)["C4"], "theta4")


def inverse_kinematics(d: Dims, pose: Pose) -> np.ndarray:
    """All 8 input sets (theta_1, theta_2, theta_3) (rad) for a platform pose: eq. (10).

    Row k holds the roots (k >> 2 & 1, k >> 1 & 1, k & 1) of theta_1, theta_2, theta_3 (0 = the
    ``+`` root of ``solve_trig``). With the 2 follower roots of theta_4, 16 configurations.

    Raises:
        InvalidParameters: a limb cannot reach the pose.
    """
    a, c = base_points(d), _end_points(d, pose)
    roots = [_proximal_roots(d, a[i], c[i], f"theta{i + 1}")[0] for i in range(3)]
    return np.array(list(itertools.product(*roots)))


def distal_angles(d: Dims, theta: np.ndarray, pose: Pose) -> np.ndarray:
    """Absolute angles (4,) rad of the distal links B_d C_d (direction (C_d - B_d) / l2)."""
    r = _end_points(d, pose) - elbow_points(d, theta)
    return np.arctan2(-r[:, 2], r[:, 0])


def loop_residuals(d: Dims, theta: np.ndarray, pose: Pose) -> np.ndarray:
    """|C_d - B_d| - l2 (4,) m for theta_1..theta_4: zero when every limb closes."""
    r = _end_points(d, pose) - elbow_points(d, theta)
    return np.hypot(r[:, 0], r[:, 2]) - d.l2


def _dyad_terms(d: Dims, theta: np.ndarray, pose: Pose) -> tuple[np.ndarray, np.ndarray]:
    """In-plane C_d - B_d (4, 2) and dB_d/dtheta_d / l2 = (sin, cos) (4, 2)."""
    r = _end_points(d, pose) - elbow_points(d, theta)
    return r[:, [0, 2]], np.stack([np.sin(theta), np.cos(theta)], axis=1)


def jacobians(d: Dims, theta: np.ndarray, pose: Pose) -> tuple[np.ndarray, np.ndarray]:
    """Velocity Jacobians of eq. (11): J_p (xp', zp', alpha')^T = J_q (theta_1', theta_2', theta_3')^T.

    Entries f_ij as printed; g_ii = 2 l2 (sin theta_i (x_C - x_B) + cos theta_i (z_C - z_B)), the
    time derivative of the printed constraints (the printed g_ii carry the opposite sign).
    """
    r, w = _dyad_terms(d, np.append(np.asarray(theta)[:3], 0.0), pose)
    sa, ca = np.sin(pose.alpha), np.cos(pose.alpha)
    jp = np.zeros((3, 3))
    jp[:, :2] = 2.0 * r[:3]
    jp[2, 2] = d.l3 * (sa * r[2, 0] + ca * r[2, 1])
    jq = np.diag(2.0 * d.l2 * np.einsum("ij,ij->i", w[:3], r[:3]))
    return jp, jq


def _solve(m: np.ndarray, rhs: np.ndarray, what: str, max_cond: float = 1e12) -> np.ndarray:
    cond = float(np.linalg.cond(m))
    if not np.isfinite(cond) or cond > max_cond:
        raise SingularConfiguration(cond, what)
    return np.linalg.solve(m, rhs)


@dataclass(frozen=True)
class State:
    """Motion of the whole mechanism at one instant (SI, base frame).

    Attributes:
        pose: platform pose.
        x_dot, x_ddot: (3,) platform rates (xp', zp', alpha') and accelerations.
        theta, theta_dot, theta_ddot: (4,) proximal angles theta_1..theta_4 and their rates.
    """

    pose: Pose
    x_dot: np.ndarray
    x_ddot: np.ndarray
    theta: np.ndarray
    theta_dot: np.ndarray
    theta_ddot: np.ndarray


def _point_motion(pose: Pose, x_dot: np.ndarray, x_ddot: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """In-plane velocity and acceleration (2,) of a platform point at in-plane offset r (2,) from p."""
    w, e = x_dot[2], x_ddot[2]
    turn = np.array([r[1], -r[0]])  # e_y x (r_x, 0, r_z) in (x, z)
    return x_dot[:2] + w * turn, x_ddot[:2] + e * turn - w * w * r


def _end_motion(d: Dims, state_pose: Pose, x_dot: np.ndarray, x_ddot: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Velocities and accelerations (4, 2) of C1, C1, C3, C4."""
    c = _end_points(d, state_pose)[:, [0, 2]]
    vel, acc = zip(*(_point_motion(state_pose, x_dot, x_ddot, ci - c[0]) for ci in c))
    return np.array(vel), np.array(acc)


def motion_state(
    d: Dims,
    theta: np.ndarray,
    theta_dot: np.ndarray,
    theta_ddot: np.ndarray,
    pose: Pose,
    theta4: float,
) -> State:
    """Platform and follower motion from the inputs: eqs. (12), (15) and the follower theta_4.

    Args:
        theta, theta_dot, theta_ddot: (3,) inputs theta_1..theta_3 (rad, rad/s, rad/s^2).
        pose: the assembled pose for ``theta`` (one of ``forward_kinematics``).
        theta4: the assembled follower angle (one of ``follower_angles``).

    Raises:
        SingularConfiguration: J_p (parallel singularity) or limb III (serial) is singular.
    """
    theta4_all = np.append(np.asarray(theta, dtype=float), theta4)
    td, tdd = np.asarray(theta_dot, float), np.asarray(theta_ddot, float)
    jp, jq = jacobians(d, theta4_all, pose)
    x_dot = _solve(jp, jq @ td, "J_p of eq. (12)")
    vc, _ = _end_motion(d, pose, x_dot, np.zeros(3))
    r, w = _dyad_terms(d, theta4_all, pose)
    vb = d.l2 * w[:3] * td[:, None]
    rel = vc[:3] - vb  # d/dt (C - B), limbs 1..3
    sa, ca = np.sin(pose.alpha), np.cos(pose.alpha)
    jp_dot = np.zeros((3, 3))
    jp_dot[:, :2] = 2.0 * rel
    jp_dot[2, 2] = d.l3 * (ca * x_dot[2] * r[2, 0] + sa * rel[2, 0] - sa * x_dot[2] * r[2, 1] + ca * rel[2, 1])
    wdot = np.stack([np.cos(theta4_all[:3]), -np.sin(theta4_all[:3])], axis=1) * td[:, None]
    jq_dot = np.diag(2.0 * d.l2 * (np.einsum("ij,ij->i", wdot, r[:3]) + np.einsum("ij,ij->i", w[:3], rel)))
    x_ddot = _solve(jp, jq @ tdd + jq_dot @ td - jp_dot @ x_dot, "J_p of eq. (15)")
    t4d = follower_rate(d, theta4_all, pose, x_dot)
    # differentiated twice: |C' - B'|^2 + (C - B).(C'' - B'') = 0, B'' = l2 (w theta'' + w' theta'^2)
    vc, ac = _end_motion(d, pose, x_dot, x_ddot)
    rel4 = vc[3] - d.l2 * w[3] * t4d
    u4 = np.array([np.cos(theta4), -np.sin(theta4)])
    t4dd = (rel4 @ rel4 + r[3] @ ac[3] - d.l2 * t4d**2 * (r[3] @ u4)) / (d.l2 * float(w[3] @ r[3]))
    return State(pose, x_dot, x_ddot, theta4_all, np.append(td, t4d), np.append(tdd, t4dd))


def follower_rate(d: Dims, theta: np.ndarray, pose: Pose, x_dot: np.ndarray) -> float:
    """Follower rate theta_4' (rad/s) for platform rates x_dot from limb III's dyad, (C4 - B4).(C4' - B4') = 0.

    Args:
        theta: (4,) theta_1..theta_4 (rad).

    Raises:
        SingularConfiguration: limb III stretched or folded (its rate is undefined).
    """
    vc, _ = _end_motion(d, pose, np.asarray(x_dot, dtype=float), np.zeros(3))
    r, w = _dyad_terms(d, np.asarray(theta, dtype=float), pose)
    den = d.l2 * float(w[3] @ r[3])
    if abs(den) < 1e-12 * d.l2**2:
        raise SingularConfiguration(np.inf, "limb III stretched or folded: theta_4 rate undefined")
    return float(r[3] @ vc[3]) / den


@dataclass(frozen=True)
class BodyMotion:
    """Rigid-body state at one instant, base frame: absolute angle about +y (rad), COM position (3,) m,
    COM velocity / acceleration (3,) m/s, m/s^2, angular velocity / acceleration (3,) rad/s, rad/s^2."""

    angle: float
    com: np.ndarray
    v_com: np.ndarray
    a_com: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray


def link_motion(d: Dims, s: State) -> dict[str, BodyMotion]:
    """Every body's COM (bars: mid-point; platform: p), its velocity and acceleration: eqs. (16)-(29)."""
    out: dict[str, BodyMotion] = {}
    vc, ac = _end_motion(d, s.pose, s.x_dot, s.x_ddot)
    phi2 = distal_angles(d, s.theta, s.pose)
    base = base_points(d)
    to3 = lambda v2: np.array([v2[0], 0.0, v2[1]])
    for i in range(4):
        c1 = d.l2 * direction(np.pi + s.theta[i])
        w1, e1 = s.theta_dot[i] * EY, s.theta_ddot[i] * EY
        vb = cross(w1, c1)  # (16)
        ab = cross(e1, c1) + cross(w1, cross(w1, c1))  # (17)
        out[f"link{i + 1}1"] = BodyMotion(float(np.pi + s.theta[i]), base[i] + c1 / 2.0, vb / 2.0, ab / 2.0,
                                          w1, e1)  # (18)-(19)
        c2 = direction(phi2[i])
        v_c, a_c = to3(vc[i]), to3(ac[i])
        w2 = cross(c2, v_c - vb) / d.l2  # (21), (28)
        e2 = cross(c2, a_c - ab) / d.l2  # (23), (29)
        out[f"link{i + 1}2"] = BodyMotion(float(phi2[i]), base[i] + c1 + d.l2 / 2.0 * c2, (vb + v_c) / 2.0,
                                          (ab + a_c) / 2.0, w2, e2)  # (26)-(27)
    out["platform"] = BodyMotion(s.pose.alpha, platform_points(d, s.pose)["p"], to3(s.x_dot[:2]),
                                 to3(s.x_ddot[:2]), s.x_dot[2] * EY, s.x_ddot[2] * EY)
    return out
