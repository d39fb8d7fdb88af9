"""Where the ten-bar's methods fail, and what takes over.

- The patent's purely kinematic split: with the two motors alone the closure leaves one motion
  free (the five-bar unit has DOF 2 and one motor), so positions, rates and accelerations of the
  passive joints are undetermined; only the dynamics (spring, damper, gravity, inertia) fixes them.
- Integration without constraint stabilisation drifts off the closures; Baumgarte terms bound the
  drift, projection removes it.
- Singular poses: the distance of every loop from its dead-centre pose along a motion.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from scipy.linalg import null_space

from mechkit import core
from mechkit.loading import from_params
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar import kinematics as tk
from mechkit.mechanisms.ten_bar.params import MOTORS, TenBarParams

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism


@dataclass(frozen=True)
class KinematicSplit:
    """What the motors alone leave free at a configuration.

    Attributes:
        nullity: dimension of the joint motions (motors held) that keep every loop closed.
        direction: (nv,) unit joint-rate vector of that motion (rad/s per unit).
        five_bar_nullity: the same for the five-bar unit alone with only its R1 motor given.
    """

    nullity: int
    direction: np.ndarray
    five_bar_nullity: int


def kinematic_split(mechanism: Mechanism, q: np.ndarray) -> KinematicSplit:
    """Null space of the closure Jacobian with the motor columns held (the patent's kinematic split).

    Args:
        mechanism: the ten-bar.
        q: an assembled configuration (nq,).

    Returns:
        The null space's dimension, its direction (nv,) and the five-bar's own nullity.
    """
    J = mechanism.closure_jacobian(q)
    motors = [mechanism.v_index(m) for m in MOTORS]
    free = np.setdiff1d(np.arange(J.shape[1]), motors)
    null = null_space(J[:, free])
    direction = np.zeros(J.shape[1])
    direction[free] = null[:, 0]
    unit = tk.DimensionReduction(mechanism).units[0]
    five_q = np.array([q[mechanism.q_index(j)] for j in unit.model.names[1:]])
    Ju = core.closure_jacobian(unit.closure_model, unit.closure_data, five_q)
    r1 = unit.model.joints[unit.model.getJointId("R1")].idx_v
    five_free = np.setdiff1d(np.arange(Ju.shape[1]), [r1])
    return KinematicSplit(null.shape[1], direction, null_space(Ju[:, five_free]).shape[1])


STABILISATIONS = (
    ("no stabilisation", None, False),
    ("Baumgarte Kp = 100, Kd = 20", (100.0, 20.0), False),
    ("projection", None, True),
)
"""(label, Baumgarte gains (1/s^2, 1/s) or None, project after each step) compared by `drift`."""


def drift(
    mechanism: Mechanism, t_end: float, dt: float, baumgarte: tuple[float, float] | None, project: bool
) -> td.Trajectory:
    """A stretch of the deployment from stowed with a chosen stabilisation (Pinocchio route).

    Baumgarte gains stay set on the core's constraint models (see docs/core_requests.md), so a
    stabilised run uses its own copy of the mechanism and leaves the caller's untouched.

    Args:
        mechanism: the ten-bar.
        t_end: end time, s.
        dt: RK4 step, s.
        baumgarte: Baumgarte gains (Kp, Kd), or None.
        project: project after every step.

    Returns:
        The trajectory.
    """
    own = mechanism if baumgarte is None else from_params(mechanism.spec, mechanism.params)
    system = td.PinocchioDeployment(own, baumgarte=baumgarte)
    return td.deploy(system, own.home_q, dt, t_end, project=project)


def loop_margins(params: TenBarParams, angles: np.ndarray) -> dict[str, np.ndarray]:
    """Sine of the angle at each loop's closing hinge (R7, R9, R8) along a trajectory (0: singular).

    Args:
        params: the parameters.
        angles: (N, 9) joint angles in `td.JOINT_ORDER`.

    Returns:
        Loop -> (N,) margins (-).
    """
    i1, i3, i5 = (td.JOINT_ORDER.index(j) for j in ("R1", "R3", "R5"))
    rows = [geo.pose(params, a[i1], a[i3], a[i5]).margins for a in angles]
    return {k: np.array([r[k] for r in rows]) for k in rows[0]}
