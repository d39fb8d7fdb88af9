"""The cone scene of the 2-DOF spherical platform: the platform normal sweeps a cone about Z0 at constant
speed (the paper's Figs. 5-7), as an attitude law with its derivatives and as assembled poses.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.spherical_2dof.joint_state import state

if TYPE_CHECKING:
    from mechkit.bases import HeldMotion
    from mechkit.mechanism import Mechanism

__all__ = [
    "CONE_HALF_ANGLE",
    "CONE_PERIOD",
    "SHIP",
    "cone_attitude",
    "cone_scene",
    "cone_scene_times",
    "cone_times",
    "isolation_figures",
    "isolation_lines",
    "isolation_points",
    "isolation_study",
    "on_ship",
    "ship_figures",
    "ship_lines",
    "ship_motion",
    "ship_study",
]

#: Cone scene: the paper's "cone angle 30 deg" (錐角) read as the apex angle: half angle 15 deg.
CONE_HALF_ANGLE = math.radians(15.0)
#: Cone scene: one turn of the normal about Z0 in 2 s (ours: "constant speed" is all the paper says).
CONE_PERIOD = 2.0


def cone_attitude(
    t: np.ndarray | float, half_angle: float = CONE_HALF_ANGLE, period: float = CONE_PERIOD
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cone scene: the platform normal n = [s(g) c(psi), s(g) s(psi), c(g)], psi = 2 pi t / period.

    With n = Rx(phi_x) Ry(phi_y) e_z: phi_y = asin(s(g) c(psi)), phi_x = atan(-tan(g) s(psi)).

    Args:
        t: time(s), s.
        half_angle: g, the cone's half angle (rad).
        period: one turn, s.

    Returns:
        phi, phi', phi'' as arrays (..., 2) (rad, rad/s, rad/s^2), columns (roll, pitch).

    Raises:
        InvalidParameters: a half angle outside [0, 90) deg, or a period not > 0.
    """
    if not 0.0 <= half_angle < math.pi / 2:
        raise InvalidParameters("half_angle", half_angle, "must lie in [0, 90) deg")
    if not period > 0.0:
        raise InvalidParameters("period", period, "must be > 0 s")
    w = 2.0 * math.pi / period
    psi = w * np.asarray(t, dtype=float)
    sg, tg = math.sin(half_angle), math.tan(half_angle)
    g, g1, g2 = sg * np.cos(psi), -sg * w * np.sin(psi), -sg * w**2 * np.cos(psi)
    root = np.sqrt(1.0 - g**2)
    h, h1, h2 = -tg * np.sin(psi), -tg * w * np.cos(psi), tg * w**2 * np.sin(psi)
    den = 1.0 + h**2
    phi = np.stack([np.arctan(h), np.arcsin(g)], axis=-1)
    phi_d = np.stack([h1 / den, g1 / root], axis=-1)
    phi_dd = np.stack([h2 / den - 2.0 * h * h1**2 / den**2, g2 / root + g * g1**2 / root**3], axis=-1)
    return phi, phi_d, phi_dd


def cone_times(samples: int) -> np.ndarray:
    """``samples`` instants over one turn of the cone scene (s).

    Args:
        samples: how many instants.

    Returns:
        (samples,) times, s, the period's end excluded.
    """
    return np.linspace(0.0, CONE_PERIOD, samples, endpoint=False)


def cone_scene(mech: Mechanism) -> list[np.ndarray]:
    """One turn of the cone scene as assembled configurations (`mechkit snapshot spherical_2dof --scene cone`).

    Args:
        mech: the platform.

    Returns:
        The configurations (nq,).
    """
    phi, phi_d, phi_dd = cone_attitude(np.linspace(0.0, CONE_PERIOD, 73))
    return [state(mech, *x)[0] for x in zip(phi, phi_d, phi_dd, strict=True)]


def cone_scene_times(mech: Mechanism, poses: int) -> np.ndarray:
    """Times (s) of the cone scene's poses: uniform over one turn, both ends included.

    Args:
        mech: the platform.
        poses: the number of poses.

    Returns:
        (poses,) times, s.
    """
    return np.linspace(0.0, CONE_PERIOD, poses)


#: On a ship (ours: a moderate sea): roll 10 deg over 8 s, pitch 4 deg over 6 s, heave 0.5 m over 7 s,
#: as (amplitude, period (s)) of x, y, z (m), roll, pitch, yaw (rad).
SHIP = ((0.0, 1.0), (0.0, 1.0), (0.5, 7.0), (math.radians(10.0), 8.0), (math.radians(4.0), 6.0), (0.0, 1.0))
#: The platform kept level: its normal (its own z) along the world's z.
LEVEL = ((0.0, 0.0, 1.0), (0.0, 0.0, 1.0))


def ship_motion(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The ship's motion `SHIP` at a time: each coordinate a sine of its amplitude and period.

    Args:
        t: time (s).

    Returns:
        The carrier's pose (x, y, z, roll, pitch, yaw; m, rad), its rates and accelerations (6,).
    """
    amp, w = np.array([a for a, _ in SHIP]), 2 * np.pi / np.array([p for _, p in SHIP])
    return amp * np.sin(w * t), amp * w * np.cos(w * t), -amp * w * w * np.sin(w * t)


def on_ship(mech: Mechanism, duration: float = 24.0, samples: int = 241) -> HeldMotion:
    """The platform held level on the ship: the motor inputs, torques and every reaction
    (`mechkit.bases.held_motion`).

    Args:
        mech: the platform on its fixed ground.
        duration: s.
        samples: samples of the motion.

    Returns:
        The `HeldMotion` (its study's efforts at base_* are the ship's wrench on the platform's base).
    """
    from mechkit.bases import base_motion, held_motion, with_base

    moving = with_base(mech, "moving")
    return held_motion(
        moving, base_motion.from_callable(ship_motion, np.linspace(0.0, duration, samples)), "platform", LEVEL
    )


def isolation_points(
    mech: Mechanism,
    frequencies: Sequence[float],
    bandwidths: Sequence[float],
    amplitude: float = math.radians(5.0),
    rotor_inertia: float = 0.05,
) -> list:
    """The isolation chart's points: the carrier rolling at each frequency, the drives position servos of
    each bandwidth holding the platform level (`mechkit.bases.isolation`).

    Args:
        mech: the platform on its fixed ground.
        frequencies: the carrier's roll frequencies (Hz).
        bandwidths: the servos' bandwidths (Hz).
        amplitude: the carrier's roll amplitude (rad; ours 5 deg).
        rotor_inertia: each motor's reflected rotor inertia (kg m^2; ours).

    Returns:
        The `IsolationPoint`s, bandwidth by bandwidth.
    """
    from mechkit.bases.isolation import holding_table, isolation_point, on_carrier

    carried = on_carrier(mech, rotor_inertia)
    table = holding_table(carried, "platform", LEVEL, amplitude)
    return [isolation_point(carried, table, amplitude, f, b) for b in bandwidths for f in frequencies]


#: The isolation study's carrier roll frequencies and servo bandwidths (Hz; ours).
ISOLATION_FREQUENCIES, ISOLATION_BANDWIDTHS = (0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0), (1.0, 4.0)


def ship_study(mech: Mechanism) -> dict:
    """The platform held level on the ship (`on_ship`), with the carried mechanism and its motion to draw.

    Args:
        mech: the platform on its fixed ground.

    Returns:
        "held": the `HeldMotion`; "snapshot": (the platform on its moving base, q (N, nq), figure name).
    """
    from mechkit.bases import with_base

    held = on_ship(mech)
    return {"held": held, "snapshot": (with_base(mech, "moving"), held.study.q, "bases_spherical_ship_snapshot")}


def ship_lines(data: dict) -> list[str]:
    """The ship study's numbers: the tilt left, the inputs, the motor torques, the carrier's vertical force.

    Args:
        data: `ship_study`'s data (its "held" is read).

    Returns:
        The lines.
    """
    held, study = data["held"], data["held"].study
    lines = [f"level to {float(np.max(np.abs(held.tilt))):.2g} rad over {study.t[-1]:g} s ({len(study.t)} samples)"]
    lines += [
        f"input {n}: {held.inputs[:, k].min():.4g} .. {held.inputs[:, k].max():.4g} rad"
        for k, n in enumerate(held.names)
    ]
    lines += [f"motor torque {n}: {study.effort(n).min():.4g} .. {study.effort(n).max():.4g} N m" for n in held.names]
    lines.append(
        f"carrier's vertical force: {study.effort('base_z').min():.4g} .. {study.effort('base_z').max():.4g} N"
    )
    return lines


def ship_figures(data: dict, folder: Path) -> list[Path]:
    """The ship study's chart (`mechkit.bases.chart.held_chart`) in `folder`.

    Args:
        data: `ship_study`'s data.
        folder: where the PNG goes.

    Returns:
        The file written.
    """
    from mechkit.bases.chart import held_chart

    return [held_chart(data["held"], folder / "bases_spherical_ship.png", "spherical platform held level on a ship")]


def isolation_study(mech: Mechanism) -> list:
    """`isolation_points` at `ISOLATION_FREQUENCIES` and `ISOLATION_BANDWIDTHS` (14 simulations: minutes).

    Args:
        mech: the platform on its fixed ground.

    Returns:
        The `IsolationPoint`s, bandwidth by bandwidth.
    """
    return isolation_points(mech, ISOLATION_FREQUENCIES, ISOLATION_BANDWIDTHS)


def isolation_lines(points: list) -> list[str]:
    """One line per point: frequency, bandwidth, the simulated residual tilt ratio and the linear servo's.

    Args:
        points: `isolation_study`'s points.

    Returns:
        One line per point.
    """
    return [
        f"{p.frequency:g} Hz, {p.bandwidth:g} Hz servos: {p.ratio:.3g} (linear servo {p.theory:.3g})" for p in points
    ]


def isolation_figures(points: list, folder: Path) -> list[Path]:
    """The isolation chart (`mechkit.bases.chart.isolation_chart`) in `folder`.

    Args:
        points: `isolation_study`'s points.
        folder: where the PNG goes.

    Returns:
        The file written.
    """
    from mechkit.bases.chart import isolation_chart

    return [isolation_chart(points, folder / "bases_spherical_isolation.png", "spherical platform isolation")]
