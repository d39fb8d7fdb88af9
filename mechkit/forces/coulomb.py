"""Joint friction of constant size (URDF `<dynamics friction>`, MJCF `frictionloss`), regularised near
zero speed, and the regularisation every friction element shares.

The law (ours, stated for every friction element of mechkit): effort = -F tanh(x_dot / SPEED_THRESHOLD)
with F the friction's size (N m or N) and x_dot the joint's rate. tanh reaches 0.76 F at the
threshold and 0.995 F at three times it; below it the joint behaves as a viscous damper of
F / threshold, so a mechanism that friction would hold creeps instead of sticking (no stick-slip
event). The power, -F x_dot tanh(x_dot / threshold), is never positive: friction only dissipates.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters
from mechkit.forces.element import ForceElement, ForceState, Load

#: Rate (rad/s or m/s) at which the regularised friction reaches tanh(1) = 0.76 of its size (ours:
#: two orders below the ten-bar's motor rates, and a near-zero-speed damping F / threshold that an
#: explicit adaptive integrator still steps through).
SPEED_THRESHOLD = 1e-2


def smooth_sign(rate: np.ndarray | float, threshold: float = SPEED_THRESHOLD) -> np.ndarray | float:
    """tanh(rate / threshold): the regularised sign of a friction's rate.

    Args:
        rate: the joint rate(s) (rad/s or m/s), a scalar or an array of any shape.
        threshold: the regularisation's rate (rad/s or m/s, > 0).

    Returns:
        The regularised sign (dimensionless, in [-1, 1]), of the shape of `rate`.
    """
    return np.tanh(np.asarray(rate) / threshold)


def one_freedom_joint(model: pin.Model, joint: str, what: str) -> int:
    """The velocity index of a one-freedom joint, by name.

    Args:
        model: the tree's Pinocchio model.
        joint: the joint's name.
        what: what asks for the joint (named in the error).

    Returns:
        The joint's index into v (nv,).

    Raises:
        InvalidParameters: no such joint, or a joint of several freedoms.
    """
    if not isinstance(joint, str) or not model.existJointName(joint):
        raise InvalidParameters(what, joint, f"no such joint; joints: {list(model.names[1:])}")
    jm = model.joints[model.getJointId(joint)]
    if jm.nv != 1:
        raise InvalidParameters(what, joint, f"a {jm.shortname()} joint has {jm.nv} freedoms: one-freedom joints only")
    return jm.idx_v


class CoulombFriction(ForceElement):
    """Constant-size friction on one-freedom joints: effort = -F tanh(rate / threshold).

    Args:
        model: the tree.
        sizes: joint name -> F (N m or N, >= 0).
        threshold: the regularisation's rate (rad/s or m/s, > 0).
        name: the element's name.

    Raises:
        InvalidParameters: an unknown or multi-freedom joint, a negative size, a threshold <= 0.
    """

    role = "dissipative"
    friction = True

    def __init__(
        self,
        model: pin.Model,
        sizes: Mapping[str, float],
        threshold: float = SPEED_THRESHOLD,
        name: str = "joint friction",
    ):
        if not threshold > 0:
            raise InvalidParameters("threshold", threshold, "the friction's speed threshold must be > 0")
        self.name, self.threshold = name, float(threshold)
        self.sizes = dict(sizes)
        for joint, size in self.sizes.items():
            if not size >= 0:
                raise InvalidParameters(f"friction on {joint}", size, "must be >= 0")
        for joint in self.sizes:
            if not isinstance(joint, str) or not model.existJointName(joint):
                raise InvalidParameters(
                    "friction",
                    joint,
                    f"no such tree joint; joints: {list(model.names[1:])} (a loop-cut joint's: CutJointFriction)",
                )
        self._v = np.array([one_freedom_joint(model, j, "friction") for j in self.sizes], dtype=int)
        self._f = np.array(list(self.sizes.values()), dtype=float)
        self._nv = model.nv

    def load(self, state: ForceState) -> Load:
        """The friction efforts at a state and their power.

        Args:
            state: the state (its v is read).

        Returns:
            The `Load`: generalised forces (nv,) (N m or N) at the joints with friction, no wrenches, and
            their power (W, <= 0).
        """
        rate = state.v[self._v]
        effort = -self._f * smooth_sign(rate, self.threshold)
        tau = np.zeros(self._nv)
        tau[self._v] = effort
        return Load(tau, None, float(effort @ rate))
