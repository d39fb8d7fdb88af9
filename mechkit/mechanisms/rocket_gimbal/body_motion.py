"""Analytic motion of every body of the engine gimbal from the hinge angles (numpy only).

Given (alpha, beta) and their first and second time derivatives, this gives the engine's and the
bracket's angular velocity and acceleration, and for each U-P-S actuator its length, Hooke angles,
axis direction and their rates and accelerations, all in the paper frame O-xyz (z along the nozzle),
from the geometry alone (no Pinocchio). The Hooke joint at a frame pivot turns first about the
frame's x axis (angle t1), then about the cross's y axis (t2): the actuator axis is
``u = Rx(t1) Ry(t2) e_z``, the URDF's `*_swing_1`, `*_swing_2` joints; the stroke is L - l0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.base.spatial import cross, rot_x
from mechkit.mechanisms.rocket_gimbal.kinematics import GimbalGeometry, attitude, hinge_axes

__all__ = ["GimbalMotion", "LegMotion", "gimbal_motion"]

_EX, _EY, _EZ = np.eye(3)


@dataclass(frozen=True)
class LegMotion:
    """One actuator's motion, paper frame.

    Attributes:
        length, length_rate, length_acc: L (m), dL/dt (m/s), d2L/dt2 (m/s^2).
        hooke, hooke_rate, hooke_acc: (2,) Hooke angles (t1, t2) rad and their derivatives.
        axis: (3,) unit actuator axis u (frame pivot -> engine pivot).
        hooke_axes: (3, 2) unit Hooke axes e1 (fixed) and e2 (turned by t1).
        omega, alpha: (3,) angular velocity (rad/s) and acceleration (rad/s^2) of cylinder and rod.
        axis_rate, axis_acc: (3,) du/dt, d2u/dt2.
    """

    length: float
    length_rate: float
    length_acc: float
    hooke: np.ndarray
    hooke_rate: np.ndarray
    hooke_acc: np.ndarray
    axis: np.ndarray
    hooke_axes: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    axis_rate: np.ndarray
    axis_acc: np.ndarray


@dataclass(frozen=True)
class GimbalMotion:
    """The whole mechanism's motion at one instant, paper frame.

    Attributes:
        angles, rates, accs: (2,) (alpha, beta) rad, rad/s, rad/s^2.
        rotation: (3, 3) engine attitude R.
        hinge_axes: (3, 2) unit axes x1 (bracket hinge) and y2 (engine hinge).
        omega, alpha: (3,) engine angular velocity and acceleration.
        bracket_omega, bracket_alpha: (3,) the bracket's.
        engine_pivots: (2, 3) current positions of A and B, m.
        legs: (leg A, leg B).
    """

    angles: np.ndarray
    rates: np.ndarray
    accs: np.ndarray
    rotation: np.ndarray
    hinge_axes: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    bracket_omega: np.ndarray
    bracket_alpha: np.ndarray
    engine_pivots: np.ndarray
    legs: tuple[LegMotion, LegMotion]


def _leg(frame_pivot: np.ndarray, point: np.ndarray, velocity: np.ndarray, acc: np.ndarray) -> LegMotion:
    d = point - frame_pivot
    length = float(np.linalg.norm(d))
    u = d / length
    length_rate = float(u @ velocity)
    u_rate = (velocity - length_rate * u) / length
    length_acc = float(u @ acc + length * (u_rate @ u_rate))
    u_acc = (acc - length_acc * u - 2.0 * length_rate * u_rate) / length
    t2 = float(np.arcsin(np.clip(u[0], -1.0, 1.0)))
    t1 = float(np.arctan2(-u[1], u[2]))
    e1, e2 = _EX, rot_x(t1) @ _EY
    basis = np.column_stack([cross(e1, u), cross(e2, u)])
    if np.linalg.svd(basis, compute_uv=False)[-1] < 1e-9:
        raise SingularConfiguration(float("inf"), "actuator Hooke joint at its gimbal lock (t2 = +-90 deg)")
    rate = np.linalg.lstsq(basis, u_rate, rcond=None)[0]
    omega = rate[0] * e1 + rate[1] * e2
    twist = rate[0] * rate[1] * cross(e1, e2)  # d(e2)/dt = t1_rate e1 x e2
    rhs = u_acc - cross(omega, cross(omega, u)) - cross(twist, u)
    acc2 = np.linalg.lstsq(basis, rhs, rcond=None)[0]
    alpha = acc2[0] * e1 + acc2[1] * e2 + twist
    return LegMotion(
        length,
        length_rate,
        length_acc,
        np.array([t1, t2]),
        rate,
        acc2,
        u,
        np.column_stack([e1, e2]),
        omega,
        alpha,
        u_rate,
        u_acc,
    )


def gimbal_motion(geo: GimbalGeometry, angles: np.ndarray, rates: np.ndarray, accs: np.ndarray) -> GimbalMotion:
    """Every body's motion from (alpha, beta) and their derivatives (rad, rad/s, rad/s^2).

    Args:
        geo: the geometry.
        angles: (alpha, beta), rad.
        rates: their rates, rad/s.
        accs: their accelerations, rad/s^2.

    Returns:
        Every body's angular velocity and acceleration, and per servo its length, Hooke angles, axis and their
            derivatives (paper frame O-xyz).

    Raises:
        InvalidParameters: angles, rates or accelerations that are not two finite values.
    """
    angles, rates, accs = (np.asarray(x, dtype=float) for x in (angles, rates, accs))
    for name, x in (("angles", angles), ("rates", rates), ("accs", accs)):
        if x.shape != (2,) or not np.all(np.isfinite(x)):
            raise InvalidParameters(name, x, "need two finite values (alpha, beta) in rad, rad/s or rad/s^2")
    rotation = attitude(*angles)
    x1, y2 = hinge_axes(angles[0])
    omega = rates[0] * x1 + rates[1] * y2
    alpha = accs[0] * x1 + accs[1] * y2 + rates[0] * rates[1] * cross(x1, y2)
    pivots = geo.engine_pivots @ rotation.T
    legs = []
    for frame_pivot, p in zip(geo.frame_pivots, pivots):
        v = cross(omega, p)
        a = cross(alpha, p) + cross(omega, v)
        legs.append(_leg(frame_pivot, p, v, a))
    return GimbalMotion(
        angles,
        rates,
        accs,
        rotation,
        np.column_stack([x1, y2]),
        omega,
        alpha,
        rates[0] * x1,
        accs[0] * x1,
        pivots,
        (legs[0], legs[1]),
    )
