"""The 2T1R's rate analysis (Huang, Shen, Li, Zhu, Yang), numpy only: velocities and accelerations.

Velocity Jacobians J_p, J_q (eq. (11)), platform rates (12) and accelerations (15), the follower
theta_4's rate and acceleration, every body's motion (16)-(29). Positions, frames and angle
conventions are those of `kinematics` (every angle a rotation about +y, base frame {o}).

Departures from the printed paper, each checked by a test:
- the printed g_ii of eq. (11) have the opposite sign of the time derivative of the printed
  constraints; we use the derivative (finite differences confirm it), so J_p v = J_q omega holds.
- k_1..k_3 of eq. (15) (lost, "scan the QR code") are derived here: J_p a = J_q eps + dJ_q omega -
  dJ_p v.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import SingularConfiguration
from mechkit.base.spatial import cross
from mechkit.mechanisms.parallel_2t1r.kinematics import (
    EY,
    Dims,
    Pose,
    base_points,
    direction,
    distal_angles,
    elbow_points,
    end_points,
    platform_points,
)

__all__ = ["BodyMotion", "State", "at_rest", "follower_rate", "jacobians", "link_motion", "motion_state"]


def _dyad_terms(d: Dims, theta: np.ndarray, pose: Pose) -> tuple[np.ndarray, np.ndarray]:
    """In-plane C_d - B_d (4, 2) and dB_d/dtheta_d / l2 = (sin, cos) (4, 2)."""
    r = end_points(d, pose) - elbow_points(d, theta)
    return r[:, [0, 2]], np.stack([np.sin(theta), np.cos(theta)], axis=1)


def jacobians(d: Dims, theta: np.ndarray, pose: Pose) -> tuple[np.ndarray, np.ndarray]:
    """Velocity Jacobians of eq. (11): J_p (xp', zp', alpha')^T = J_q (theta_1', theta_2', theta_3')^T.

    Entries f_ij as printed; g_ii = 2 l2 (sin theta_i (x_C - x_B) + cos theta_i (z_C - z_B)), the
    time derivative of the printed constraints (the printed g_ii carry the opposite sign).

    Args:
        d: the mechanism's dimensions (m).
        theta: the inputs theta_1..theta_3 (3,), rad.
        pose: a platform pose (x, z in m, alpha in rad).

    Returns:
        (J_p (3, 3), J_q (3, 3)).
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


def at_rest(pose: Pose, theta: np.ndarray, theta4: float) -> State:
    """The state of a configuration at rest (every rate and acceleration zero).

    Args:
        pose: platform pose.
        theta: (3,) inputs theta_1..theta_3 (rad).
        theta4: follower angle (rad).

    Returns:
        The state.
    """
    return State(pose, np.zeros(3), np.zeros(3), np.append(theta, theta4), np.zeros(4), np.zeros(4))


def _point_motion(pose: Pose, x_dot: np.ndarray, x_ddot: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """In-plane velocity and acceleration (2,) of a platform point at in-plane offset r (2,) from p."""
    w, e = x_dot[2], x_ddot[2]
    turn = np.array([r[1], -r[0]])  # e_y x (r_x, 0, r_z) in (x, z)
    return x_dot[:2] + w * turn, x_ddot[:2] + e * turn - w * w * r


def _end_motion(d: Dims, state_pose: Pose, x_dot: np.ndarray, x_ddot: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Velocities and accelerations (4, 2) of C1, C1, C3, C4."""
    c = end_points(d, state_pose)[:, [0, 2]]
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
        d: the mechanism's dimensions (m).
        theta: (3,) inputs theta_1..theta_3 (rad).
        theta_dot: (3,) their rates (rad/s).
        theta_ddot: (3,) their accelerations (rad/s^2).
        pose: the assembled pose for ``theta`` (one of ``forward_kinematics``).
        theta4: the assembled follower angle (one of ``follower_angles``).

    Returns:
        The state.

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
    """Follower rate theta_4' (rad/s) for platform rates x_dot from limb III's dyad,
    (C4 - B4).(C4' - B4') = 0.

    Args:
        d: the mechanism's dimensions (m).
        theta: (4,) theta_1..theta_4 (rad).
        pose: a platform pose (x, z in m, alpha in rad).
        x_dot: the platform's rates (x', z', alpha'), m/s and rad/s.

    Returns:
        theta_4', rad/s.

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
    """Every body's COM (bars: mid-point; platform: p), its velocity and acceleration: eqs. (16)-(29).

    Args:
        d: the mechanism's dimensions (m).
        s: a motion state.

    Returns:
        Body -> its motion (COM, velocity, acceleration, angle, angular velocity and acceleration; world).
    """
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
        out[f"link{i + 1}1"] = BodyMotion(
            float(np.pi + s.theta[i]), base[i] + c1 / 2.0, vb / 2.0, ab / 2.0, w1, e1
        )  # (18)-(19)
        c2 = direction(phi2[i])
        v_c, a_c = to3(vc[i]), to3(ac[i])
        w2 = cross(c2, v_c - vb) / d.l2  # (21), (28)
        e2 = cross(c2, a_c - ab) / d.l2  # (23), (29)
        out[f"link{i + 1}2"] = BodyMotion(
            float(phi2[i]), base[i] + c1 + d.l2 / 2.0 * c2, (vb + v_c) / 2.0, (ab + a_c) / 2.0, w2, e2
        )  # (26)-(27)
    out["platform"] = BodyMotion(
        s.pose.alpha,
        platform_points(d, s.pose)["p"],
        to3(s.x_dot[:2]),
        to3(s.x_ddot[:2]),
        s.x_dot[2] * EY,
        s.x_ddot[2] * EY,
    )
    return out
