"""Torque motors: a commanded effort within a torque-speed envelope (a DC motor's straight line).

The envelope (ours, the linear characteristic of a DC motor at full voltage): at actuator rate w the
motor gives at most stall (1 - w / no_load) forwards and at least -stall (1 + w / no_load) backwards,
so its effort is the command clipped to [-stall (1 + w / no_load), stall (1 - w / no_load)]. A URDF
`<limit effort velocity>` gives (stall, no_load); infinite values leave the command unclipped.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters
from mechkit.forces.coulomb import one_freedom_joint
from mechkit.forces.element import ForceElement, ForceState, Load

Command = Callable[[float], float] | float


def envelope(command: float, rate: float, stall: float, no_load: float) -> float:
    """The effort (N m or N) a motor of stall effort `stall` and no-load rate `no_load` gives for `command`
    at `rate` (rad/s or m/s): the command clipped to [-stall (1 + rate / no_load), stall (1 - rate / no_load)]."""
    if math.isinf(stall):
        return command
    ratio = 0.0 if math.isinf(no_load) else rate / no_load
    return min(max(command, -stall * (1 + ratio)), stall * (1 - ratio))


class TorqueMotor(ForceElement):
    """A commanded effort on one actuator, within its torque-speed envelope.

    Args:
        row: (nv,) the actuator's row of the actuation S (its effort u acts as the generalised force
            row * u; a joint motor: a unit vector at the joint's velocity index).
        command: the commanded effort (N m or N), constant or a function of t (s).
        stall: the largest effort at rest (N m or N, > 0; inf: none).
        no_load: the rate at which the forward effort falls to zero (rad/s or m/s, > 0; inf: none).
        name: the element's (and actuator's) name.

    Raises:
        InvalidParameters: stall or no_load not > 0.
    """

    role = "source"

    def __init__(self, row: np.ndarray, command: Command, stall: float = math.inf, no_load: float = math.inf,
                 name: str = "motor"):
        if not (stall > 0 and no_load > 0):
            raise InvalidParameters(f"motor {name}", (stall, no_load), "stall effort and no-load rate must be > 0")
        self.row = np.asarray(row, dtype=float)
        self.command = command if callable(command) else (lambda t, c=float(command): c)
        self.stall, self.no_load, self.name = float(stall), float(no_load), name

    @classmethod
    def on_joint(cls, model: pin.Model, joint: str, command: Command, stall: float = math.inf,
                 no_load: float = math.inf) -> TorqueMotor:
        """A motor on a one-freedom joint, named after it."""
        row = np.zeros(model.nv)
        row[one_freedom_joint(model, joint, "motor")] = 1.0
        return cls(row, command, stall, no_load, joint)

    def effort(self, t: float, v: np.ndarray) -> float:
        """The effort (N m or N) at time t (s) and velocities v (nv,)."""
        return envelope(float(self.command(t)), float(self.row @ v), self.stall, self.no_load)

    def load(self, state: ForceState) -> Load:
        """row * effort, and its power."""
        u = self.effort(state.t, state.v)
        return Load(self.row * u, None, u * float(self.row @ state.v))
