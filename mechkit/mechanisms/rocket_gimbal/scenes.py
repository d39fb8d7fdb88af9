"""The swing scene of the engine gimbal: a conical swing in flight under thrust.

The motion law (`SwingScene`: alpha and beta as sines, with their derivatives), its thrust as
Pinocchio external forces (`thrust_fext`), and one period as assembled poses (`swing_scene`, the
`SPEC.scenes` entry). Every value of the scene is ours.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.rocket_gimbal.body_motion import GimbalMotion, gimbal_motion
from mechkit.mechanisms.rocket_gimbal.joint_state import joint_state
from mechkit.mechanisms.rocket_gimbal.params import RocketGimbalParams, geometry

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = [
    "AXIAL_ACCELERATION",
    "SwingScene",
    "flight_figures",
    "flight_lines",
    "flight_study",
    "in_flight",
    "swing_scene",
    "swing_times",
    "thrust_fext",
]


@dataclass(frozen=True)
class SwingScene:
    """A conical swing manoeuvre in flight: alpha = A sin(w t), beta = B sin(w t + phase), under thrust.

    All values are ours: a YF-100-class sea-level thrust and a swing of a few degrees at 1 Hz
    (about 25 deg/s, the order of a launcher's thrust-vector slew rate).
    """

    amplitude_alpha: float = np.radians(4.0)  # rad
    amplitude_beta: float = np.radians(4.0)  # rad
    frequency: float = 1.0  # Hz
    phase: float = np.pi / 2  # rad
    thrust: float = 1.2e6  # N, against the nozzle axis
    thrust_point: float = 1.5  # m from O along the nozzle axis (the throat)

    def __post_init__(self) -> None:
        for name, value in vars(self).items():
            if not np.isfinite(value):
                raise InvalidParameters(name, value, "must be finite")
        if self.frequency <= 0 or self.thrust < 0:
            raise InvalidParameters(
                "frequency/thrust", (self.frequency, self.thrust), "need frequency > 0, thrust >= 0"
            )

    def angles(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(alpha, beta) rad, their rates rad/s and accelerations rad/s^2 at time t (s).

        Args:
            t: time, s.

        Returns:
            ((alpha, beta), their rates, their accelerations), each (2,).
        """
        w = 2.0 * np.pi * self.frequency
        amp = np.array([self.amplitude_alpha, self.amplitude_beta])
        arg = w * t + np.array([0.0, self.phase])
        return amp * np.sin(arg), amp * w * np.cos(arg), -amp * w**2 * np.sin(arg)

    def motion(self, p: RocketGimbalParams, t: float) -> GimbalMotion:
        """The analytic motion of every body at time t.

        Args:
            p: the parameters.
            t: time, s.

        Returns:
            The motion (see `gimbal_motion`).
        """
        return gimbal_motion(geometry(p), *self.angles(t))


def thrust_fext(mech: Mechanism, q: np.ndarray, scene: SwingScene) -> list:
    """Pinocchio external forces (per joint, local frames): the thrust on the engine at q.

    Args:
        mech: the gimbal.
        q: configuration (nq,).
        scene: the scene (its thrust, N).

    Returns:
        One `pin.Force` per joint (universe first), the thrust on the engine's joint.
    """
    pin.forwardKinematics(mech.model, mech.data, q)
    engine = mech.model.getJointId("engine_hinge")
    oMi = mech.data.oMi[engine]
    n = oMi.rotation[:, 2]  # the engine frame's z is the nozzle axis
    force = -scene.thrust * n
    point = oMi.translation + scene.thrust_point * n
    fext = [pin.Force.Zero() for _ in range(mech.model.njoints)]
    fext[engine] = oMi.actInv(pin.Force(force, np.cross(point, force)))
    return fext


def swing_scene(mech: Mechanism) -> list[np.ndarray]:
    """One period of the swing scene as assembled configurations (`mechkit snapshot rocket_gimbal --scene swing`).

    Args:
        mech: the gimbal.

    Returns:
        The configurations (nq,).
    """
    scene = SwingScene()
    return [joint_state(mech, scene.motion(mech.params, t))[0] for t in np.linspace(0.0, 1.0 / scene.frequency, 120)]


def swing_times(mech: Mechanism, poses: int) -> np.ndarray:
    """Times (s) of the swing scene's poses: uniform over one period.

    Args:
        mech: the gimbal.
        poses: the number of poses.

    Returns:
        (poses,) times, s.
    """
    return np.linspace(0.0, 1.0 / SwingScene().frequency, poses)


#: The vehicle's axial acceleration in flight (ours: 2 g along the rocket's axis, world z at home, a
#: first stage late in its burn), so that the engine feels 3 g along its axis with gravity.
AXIAL_ACCELERATION = 2 * 9.81


def in_flight(mech: Mechanism, acceleration: float = AXIAL_ACCELERATION, scene: SwingScene | None = None) -> dict:
    """The swing on a vehicle accelerating along its axis, under thrust, beside the no-thrust bench.

    The flight: the gimbal on a moving base (`mechkit.bases`) whose z accelerates at `acceleration`
    from rest, the scene's thrust on the engine (`thrust_fext`), gravity as on the ground; the bench:
    the fixed gimbal under 1 g, no thrust. Both follow the swing scene's inputs (`SPEC.scenes["swing"]`).

    Args:
        mech: the gimbal on its fixed ground.
        acceleration: the vehicle's axial acceleration (m/s^2, along world z).
        scene: the swing and its thrust (default: `SwingScene()`).

    Returns:
        "bench", "flight": the motion studies (`mechkit.history.MotionResult`); "moving": the gimbal on
        its moving base.
    """
    from mechkit import motion
    from mechkit.bases import base_motion, carried, with_base

    scene = scene or SwingScene()
    law = motion.from_scene(mech, "swing")
    moving = with_base(mech, "moving")

    def vehicle(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        axial = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
        return 0.5 * acceleration * t * t * axial, acceleration * t * axial, acceleration * axial

    own = motion.from_arrays(moving, law.t, law.values, law.rates, law.accelerations, names=law.names)
    flight = carried(moving, base_motion.from_callable(vehicle, law.t, "axial acceleration"), own)
    return {
        "bench": motion.study(mech, law),
        "flight": motion.study(moving, flight, loads=lambda m, q, t: thrust_fext(m, q, scene)),
        "moving": moving,
    }


def flight_study(mech: Mechanism) -> dict:
    """`in_flight` with the moving gimbal's motion to draw.

    Args:
        mech: the gimbal on its fixed ground.

    Returns:
        `in_flight`'s studies and "snapshot": (the gimbal on its moving base, q (N, nq) in flight, figure name).
    """
    runs = in_flight(mech)
    return {**runs, "snapshot": (runs["moving"], runs["flight"].q, "bases_rocket_gimbal_snapshot")}


def flight_lines(data: dict) -> list[str]:
    """The flight study's numbers: each actuator's force range in flight and on the bench.

    Args:
        data: `flight_study`'s data.

    Returns:
        One line per actuator.
    """
    bench, flight = data["bench"], data["flight"]
    return [
        f"{j}: {flight.effort(j).min():.5g} .. {flight.effort(j).max():.5g} N in flight, "
        f"{bench.effort(j).min():.5g} .. {bench.effort(j).max():.5g} N on the bench"
        for j in bench.effort_names
    ]


def flight_figures(data: dict, folder: Path) -> list[Path]:
    """The flight study's chart (`mechkit.bases.chart.efforts_chart`) in `folder`.

    Args:
        data: `flight_study`'s data.
        folder: where the PNG goes.

    Returns:
        The file written.
    """
    from mechkit.bases.chart import efforts_chart

    runs = {"bench": data["bench"], "flight": data["flight"]}
    path = folder / "bases_rocket_gimbal_flight.png"
    return [efforts_chart(runs, list(data["bench"].effort_names), path, "gimbal in flight")]
