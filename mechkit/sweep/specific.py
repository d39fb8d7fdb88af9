"""Mechanism-specific metrics, and the table of every metric a sweep can ask for.

- rocket_gimbal `rule_error` (rad): the linear rule's worst error (|exact - rule| over both angles)
  over the stroke square +-`RULE_STROKE`, a 15 x 15 grid (the 45 x 45 grid of the mechanism's tools
  gives the same worst value at the default geometry, 9.021e-3 rad).
- ten_bar `max_motor_torque` (N m): the largest |torque| of the motors R1, R3 along the deployment
  (constrained ABA, RK4 with projection, step `TEN_BAR_DT`), and `latch_speed` (m/s, ours): the largest
  speed of any joint origin at t = deploy_time, when the motor laws stop and the panels latch (the
  cycloidal laws leave the motor-driven panels at rest there, so this is the passive DOF still moving).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.rocket_gimbal.kinematics import linear_rule_errors
from mechkit.mechanisms.rocket_gimbal.params import geometry
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.sweep.metrics import GENERIC, Metric, Samples

TEN_BAR_DT = 0.02  # s, the deployment scene's step (RK4 is unstable at 0.05 s with the default spring)
RULE_GRID = 15


def _rule_error(mech: Mechanism, _: Samples | None) -> dict[str, float]:
    return {"rule_error": linear_rule_errors(geometry(mech.params), n=RULE_GRID).worst}


def deployment_metrics(mech: Mechanism, _: Samples | None = None) -> dict[str, float]:
    """The ten-bar's deployment (RK4 with projection, step `TEN_BAR_DT`): max_motor_torque, latch_speed."""
    trajectory = td.deploy(td.PinocchioDeployment(mech), mech.home_q, TEN_BAR_DT)
    data = mech.model.createData()
    pin.forwardKinematics(mech.model, data, trajectory.q[-1], trajectory.v[-1])
    speeds = [np.linalg.norm(pin.getVelocity(mech.model, data, j, pin.LOCAL_WORLD_ALIGNED).linear)
              for j in range(1, mech.model.njoints)]
    return {"max_motor_torque": float(np.max(np.abs(trajectory.torques))), "latch_speed": float(max(speeds))}


SPECIFIC = {
    "rocket_gimbal": (
        Metric("rule_error", "rad", "the linear rule's worst error over the stroke square",
               lambda m: ["rule_error"], _rule_error, motion=False),
    ),
    "ten_bar": (
        Metric("deployment", "N m, m/s", "max_motor_torque (N m) and latch_speed (m/s) of the deployment",
               lambda m: ["max_motor_torque", "latch_speed"], deployment_metrics, motion=False),
    ),
}

DEFAULTS = {
    "rocket_gimbal": ("assembles", "branch", "rule_error"),
    "ten_bar": ("assembles", "branch", "deployment"),
}


def available(mechanism: str) -> dict[str, Metric]:
    """Every metric of a mechanism by name: the generic ones and its own."""
    return {m.name: m for m in GENERIC + SPECIFIC.get(mechanism, ())}


def resolve(mechanism: str, names: list[str] | tuple[str, ...] | None) -> tuple[Metric, ...]:
    """The metrics asked for (default: the mechanism's default set, else every generic metric).

    Raises:
        InvalidParameters: a name the mechanism does not have.
    """
    known = available(mechanism)
    chosen = names or DEFAULTS.get(mechanism) or tuple(m.name for m in GENERIC)
    for name in chosen:
        if name not in known:
            raise InvalidParameters("metric", name, f"{mechanism} has the metrics {', '.join(known)}")
    return tuple(known[name] for name in dict.fromkeys(chosen))
