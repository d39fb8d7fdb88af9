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
    """The effort a motor gives for a command: the command clipped to its torque-speed envelope.

    Args:
        command: the commanded effort (N m or N).
        rate: the actuator's rate (rad/s or m/s).
        stall: the stall effort (N m or N; inf: no envelope).
        no_load: the no-load rate (rad/s or m/s; inf: the bounds do not fall with the rate).

    Returns:
        The effort (N m or N): `command` clipped to [-stall (1 + rate / no_load), stall (1 - rate / no_load)].
    """
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

    def __init__(
        self, row: np.ndarray, command: Command, stall: float = math.inf, no_load: float = math.inf, name: str = "motor"
    ):
        if not (stall > 0 and no_load > 0):
            raise InvalidParameters(f"motor {name}", (stall, no_load), "stall effort and no-load rate must be > 0")
        self.row = np.asarray(row, dtype=float)
        self.command = command if callable(command) else (lambda t, c=float(command): c)
        self.stall, self.no_load, self.name = float(stall), float(no_load), name

    @classmethod
    def on_joint(
        cls, model: pin.Model, joint: str, command: Command, stall: float = math.inf, no_load: float = math.inf
    ) -> TorqueMotor:
        """A motor on a one-freedom joint, named after it.

        Args:
            model: the tree's Pinocchio model.
            joint: the joint's name.
            command: the commanded effort (N m or N), constant or a function of t (s).
            stall: the largest effort at rest (N m or N, > 0; inf: none).
            no_load: the rate at which the forward effort falls to zero (rad/s or m/s, > 0; inf: none).

        Returns:
            The `TorqueMotor`, its row a unit vector at the joint's velocity index.

        Raises:
            InvalidParameters: no such joint, a joint of several freedoms, stall or no_load not > 0.
        """
        row = np.zeros(model.nv)
        row[one_freedom_joint(model, joint, "motor")] = 1.0
        return cls(row, command, stall, no_load, joint)

    def effort(self, t: float, v: np.ndarray) -> float:
        """The motor's effort at a time and velocities.

        Args:
            t: time (s).
            v: (nv,) velocities.

        Returns:
            The effort (N m or N): the command at t within the envelope at the actuator's rate row . v.
        """
        return envelope(float(self.command(t)), float(self.row @ v), self.stall, self.no_load)

    def load(self, state: ForceState) -> Load:
        """row * effort, and its power.

        Args:
            state: the state (its t and v are read).

        Returns:
            The `Load`: generalised forces (nv,) row * effort, no wrenches, the power effort * (row . v) (W).
        """
        u = self.effort(state.t, state.v)
        return Load(self.row * u, None, u * float(self.row @ state.v))
