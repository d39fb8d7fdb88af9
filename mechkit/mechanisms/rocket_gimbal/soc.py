"""The engine gimbal's SKC decomposition for the SOC virtual-work solver (numpy only).

Topology: gimbal frame -> bracket (hinge Ox1) -> engine (hinge Oy2); two U-P-S servo actuators from
the frame to the engine. In SOC terms the chain frame-bracket-engine closed by servo A is a loop of
constraint degree +1 and servo B one of -1: they form ONE SKC of coupling degree 1, which cannot be
split. Order of solution (world frame, the wrench parent-on-child at the joint point):

1. ``servo_loops``: the eight tree coordinates (alpha, beta, and per servo t1, t2, stroke) with the
   two ball joints cut: 8 equations, unknowns the two efforts and the two ball forces (3 each).
2. ``engine`` (free body, 6): known ball forces and the thrust; unknown the engine hinge reaction
   (3 forces + 2 moments normal to Oy2): 6 equations, 5 unknowns; the sixth is the engine's
   equation of motion about its hinge (a consistency check).
3. ``bracket`` (free body): known the engine hinge; unknown the bracket hinge (support of the frame).
4. per servo, ``*_rod`` (free body): known its ball force; unknown the stroke joint's wrench (6, its
   axial force is the effort again); ``*_cylinder`` (free body): known the stroke joint, unknown the
   Hooke's second revolute (3 forces + 2 moments normal to e2); ``*_cross`` (free body): known that,
   unknown the first revolute, the frame pivot's support (3 forces + 2 moments normal to e1).

Body motions come from `rocket_gimbal.body_motion` (the paper's geometry), never from Pinocchio.
"""

from __future__ import annotations

import numpy as np

from mechkit.base.spatial import cross, rot_x, skew
from mechkit.mechanisms.rocket_gimbal.body_motion import GimbalMotion
from mechkit.mechanisms.rocket_gimbal.params import BodySpec, RocketGimbalParams, body_inertias, geometry
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene
from mechkit.validation.soc import BodyLoad, SKCInstant, WrenchSite

__all__ = ["PAPER_TO_WORLD", "gimbal_skcs", "soc_skcs"]

#: Rotation from the paper frame O-xyz to the world frame (nozzle down, world z up).
PAPER_TO_WORLD = rot_x(np.pi)

_FORCES = np.vstack([np.eye(3), np.zeros((3, 3))])


def _rigid(point: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """(6, 6) virtual displacement of a point (rows 0-2) and rotation (rows 3-5) of a free body.

    Virtual coordinates: the displacement of the reference point and the rotation, world.
    """
    jac = np.zeros((6, 6))
    jac[:3, :3] = np.eye(3)
    jac[:3, 3:] = -skew(point - ref)
    jac[3:, 3:] = np.eye(3)
    return jac


def _axisymmetric(mass_inertia: tuple[float, float, float], axis: np.ndarray) -> np.ndarray:
    """World inertia (3, 3) of a body symmetric about a unit axis."""
    _, transverse, axial = mass_inertia
    outer = np.outer(axis, axis)
    return transverse * (np.eye(3) - outer) + axial * outer


def _perpendicular(axis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    helper = np.eye(3)[int(np.argmin(np.abs(axis)))]
    t1 = cross(axis, helper)
    t1 /= np.linalg.norm(t1)
    return t1, cross(axis, t1)


def _revolute_released(joint: str, jacobian: np.ndarray, axis: np.ndarray) -> WrenchSite:
    """A released revolute on its child side: 3 world forces + 2 moments normal to the unit axis."""
    moments = [np.concatenate([np.zeros(3), m]) for m in _perpendicular(axis)]
    return WrenchSite(joint, jacobian, +1.0, basis=np.column_stack([_FORCES, *moments]))


def gimbal_skcs(
    motion: GimbalMotion,
    geo_frame_pivots: np.ndarray,
    bodies: BodySpec,
    engine_com: float,
    cylinder_length: float,
    rod_length: float,
    to_world: np.ndarray,
    thrust: tuple[float, float] = (0.0, 0.0),
) -> list[SKCInstant]:
    """The ordered SKCs of the gimbal at one instant.

    Args:
        motion: the analytic motion (paper frame).
        geo_frame_pivots: (2, 3) frame pivots O_A, O_B, paper frame, m.
        bodies: mass and inertias of "bracket", "engine" and, per servo "a" / "b", "*_cross",
            "*_cylinder", "*_rod".
        engine_com: distance of the engine COM from O along the nozzle axis, m.
        cylinder_length: m (COM at half length from the frame pivot).
        rod_length: m (COM at half length from the ball).
        to_world: (3, 3) rotation paper frame -> world.
        thrust: (force N, distance m from O along the nozzle axis of its point of application); the
            force acts on the engine against the nozzle axis (the exhaust leaves along +n).

    Returns:
        The SKCs in solving order; actuator names "a_stroke", "b_stroke"; joints named as in the URDF.
    """
    W = to_world
    x1, y2 = (W @ motion.hinge_axes[:, k] for k in range(2))
    n = W @ motion.rotation[:, 2]
    omega, alpha = W @ motion.omega, W @ motion.alpha
    com = engine_com * n
    com_acc = cross(alpha, com) + cross(omega, cross(omega, com))
    engine = BodyLoad(
        "engine",
        bodies["engine"][0],
        _axisymmetric(bodies["engine"], n),
        com_acc,
        omega,
        alpha,
        np.column_stack([cross(x1, com), cross(y2, com)]),
        np.column_stack([x1, y2]),
    )
    bracket = BodyLoad(
        "bracket",
        bodies["bracket"][0],
        _axisymmetric(bodies["bracket"], W @ cross(motion.hinge_axes[:, 0], motion.hinge_axes[:, 1])),
        np.zeros(3),
        W @ motion.bracket_omega,
        W @ motion.bracket_alpha,
        np.zeros((3, 2)),
        np.column_stack([x1, np.zeros(3)]),
    )
    thrust_force = -thrust[0] * n
    thrust_point = thrust[1] * n

    size = 8
    loop_bodies = [_pad(bracket, 0, size), _pad(engine, 0, size)]
    actuators, balls, free_skcs = [], [], []
    for k, name in enumerate("ab"):
        leg = motion.legs[k]
        base = 2 + 3 * k
        pivot = W @ geo_frame_pivots[k]
        u = W @ leg.axis
        e = [W @ leg.hooke_axes[:, i] for i in range(2)]
        tip = pivot + leg.length * u
        ball = W @ motion.engine_pivots[k]
        c_cyl = pivot + 0.5 * cylinder_length * u
        c_rod = tip - 0.5 * rod_length * u
        w_leg, a_leg = W @ leg.omega, W @ leg.alpha
        u_rate, u_acc = W @ leg.axis_rate, W @ leg.axis_acc
        acc_cyl = 0.5 * cylinder_length * u_acc
        arm = leg.length - 0.5 * rod_length
        acc_rod = leg.length_acc * u + 2.0 * leg.length_rate * u_rate + arm * u_acc
        loads = {}
        for body, c, acc in ((f"{name}_cylinder", c_cyl, acc_cyl), (f"{name}_rod", c_rod, acc_rod)):
            jv = np.zeros((3, size))
            jw = np.zeros((3, size))
            jw[:, base : base + 2] = np.column_stack(e)
            jv[:, base : base + 2] = np.column_stack([cross(ei, c - pivot) for ei in e])
            if body.endswith("rod"):
                jv[:, base + 2] = u
            loads[body] = BodyLoad(body, bodies[body][0], _axisymmetric(bodies[body], u), acc, w_leg, a_leg, jv, jw)
        loop_bodies += loads.values()
        actuators.append((f"{name}_stroke", np.eye(size)[base + 2]))
        # ball joint: engine (parent, frame_a) on rod (child); relative virtual displacement rod - engine
        rel = np.zeros((6, size))
        rel[:3, base : base + 2] = np.column_stack([cross(ei, tip - pivot) for ei in e])
        rel[:3, base + 2] = u
        rel[3:, base : base + 2] = np.column_stack(e)
        rel[:3, :2] -= np.column_stack([cross(x1, ball), cross(y2, ball)])
        rel[3:, :2] -= np.column_stack([x1, y2])
        balls.append(WrenchSite(f"{name}_ball_joint", rel, +1.0, components=(0, 1, 2)))

        # free rod: known ball (child side), released stroke joint (cylinder parent on rod), at the tip
        rod_free = _free(loads[f"{name}_rod"], c_rod, pivot)
        cyl_free = _free(loads[f"{name}_cylinder"], c_cyl, pivot)
        stroke_site = _rigid(tip, pivot)
        free_skcs.append(
            SKCInstant(
                f"{name}_rod",
                6,
                [rod_free],
                released=[WrenchSite(f"{name}_stroke", stroke_site, +1.0)],
                known=[WrenchSite(f"{name}_ball_joint", _rigid(tip, pivot), +1.0)],
            )
        )
        free_skcs.append(
            SKCInstant(
                f"{name}_cylinder",
                6,
                [cyl_free],
                released=[_revolute_released(f"{name}_swing_2", _rigid(pivot, pivot), e[1])],
                known=[WrenchSite(f"{name}_stroke", stroke_site, -1.0)],
            )
        )
        # the cross: COM at the pivot, turning about e1 only
        cross_load = BodyLoad(
            f"{name}_cross",
            bodies[f"{name}_cross"][0],
            _axisymmetric(bodies[f"{name}_cross"], e[0]),
            np.zeros(3),
            leg.hooke_rate[0] * e[0],
            leg.hooke_acc[0] * e[0],
            np.zeros((3, size)),
            np.outer(e[0], np.eye(size)[base]),
        )
        loop_bodies.append(cross_load)
        free_skcs.append(
            SKCInstant(
                f"{name}_cross",
                6,
                [_free(cross_load, pivot, pivot)],
                released=[_revolute_released(f"{name}_swing_1", _rigid(pivot, pivot), e[0])],
                known=[WrenchSite(f"{name}_swing_2", _rigid(pivot, pivot), -1.0)],
            )
        )

    thrust_wrench = np.concatenate([thrust_force, np.zeros(3)])
    thrust_site = np.zeros((6, size))
    thrust_site[:3, :2] = np.column_stack([cross(x1, thrust_point), cross(y2, thrust_point)])
    thrust_site[3:, :2] = np.column_stack([x1, y2])
    loop_external = [(thrust_wrench, thrust_site)]
    servo_loops = SKCInstant(
        "servo_loops", size, loop_bodies, actuators=actuators, released=balls, external=loop_external
    )
    origin = np.zeros(3)
    engine_free = _free(engine, com, origin)
    known_balls = [
        WrenchSite(f"{name}_ball_joint", _rigid(W @ motion.engine_pivots[k], origin), -1.0)
        for k, name in enumerate("ab")
    ]
    engine_skc = SKCInstant(
        "engine",
        6,
        [engine_free],
        released=[_revolute_released("engine_hinge", np.eye(6), y2)],
        known=known_balls,
        external=[(thrust_wrench, _rigid(thrust_point, origin))],
    )
    bracket_skc = SKCInstant(
        "bracket",
        6,
        [_free(bracket, origin, origin)],
        released=[_revolute_released("bracket_hinge", np.eye(6), x1)],
        known=[WrenchSite("engine_hinge", np.eye(6), -1.0)],
    )
    return [servo_loops, engine_skc, bracket_skc, *free_skcs]


def _pad(body: BodyLoad, start: int, size: int) -> BodyLoad:
    """The body with its Jacobian columns placed from `start` in an SKC of `size` coordinates."""
    jv, jw = np.zeros((3, size)), np.zeros((3, size))
    k = body.jv.shape[1]
    jv[:, start : start + k], jw[:, start : start + k] = body.jv, body.jw
    return BodyLoad(body.name, body.mass, body.inertia_com, body.com_acceleration, body.omega, body.alpha, jv, jw)


def _free(body: BodyLoad, com: np.ndarray, ref: np.ndarray) -> BodyLoad:
    """The body as a free rigid body (virtual coordinates: displacement of `ref`, rotation)."""
    jac = _rigid(com, ref)
    return BodyLoad(
        body.name,
        body.mass,
        body.inertia_com,
        body.com_acceleration,
        body.omega,
        body.alpha,
        jac[:3],
        jac[3:],
    )


def soc_skcs(p: RocketGimbalParams, motion: GimbalMotion, scene: SwingScene) -> list[SKCInstant]:
    """The SKCs of `gimbal_skcs` for these parameters (world frame), under the scene's thrust.

    Args:
        p: the parameters.
        motion: the analytic motion.
        scene: the scene (its thrust).

    Returns:
        The SKCs in solve order.
    """
    return gimbal_skcs(
        motion,
        geometry(p).frame_pivots,
        body_inertias(p),
        p.engine_com,
        p.cylinder_length,
        p.rod_length,
        PAPER_TO_WORLD,
        (scene.thrust, scene.thrust_point),
    )
