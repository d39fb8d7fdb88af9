"""The ten-bar as a design: the figures of merit a sweep asks of it (`SPEC.design_metrics`).

`deployment`: `max_motor_torque` (N m), the largest |torque| of the motors R1, R3 along the
deployment (constrained ABA, fixed steps of the simulator with projection, step `scenes.DEPLOY_STEP`), and `latch_speed`
(m/s, ours): the largest speed of any joint origin at t = deploy_time, when the motor laws stop and
the panels latch (the cycloidal laws leave the motor-driven panels at rest there, so this is the
passive DOF still moving).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.catalog.contract import DesignMetric
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar.scenes import DEPLOY_STEP


def deployment_metrics(mech: Mechanism) -> dict[str, float]:
    """The design's deployment figures of merit (step `DEPLOY_STEP`).

    Args:
        mech: the ten-bar (one design).

    Returns:
        {"max_motor_torque": N m, "latch_speed": m/s}.
    """
    trajectory = td.deploy(td.PinocchioDeployment(mech), mech.home_q, DEPLOY_STEP)
    data = mech.model.createData()
    pin.forwardKinematics(mech.model, data, trajectory.q[-1], trajectory.v[-1])
    speeds = [
        np.linalg.norm(pin.getVelocity(mech.model, data, j, pin.LOCAL_WORLD_ALIGNED).linear)
        for j in range(1, mech.model.njoints)
    ]
    return {"max_motor_torque": float(np.max(np.abs(trajectory.torques))), "latch_speed": float(max(speeds))}


DESIGN_METRICS = (
    DesignMetric(
        "deployment",
        "N m, m/s",
        "max_motor_torque (N m) and latch_speed (m/s) of the deployment",
        ("max_motor_torque", "latch_speed"),
        deployment_metrics,
    ),
)
