"""A drive as a position servo of a given bandwidth: a force element for the simulator.

The servo's effort on its one-freedom joint is u = Kp (x_c - x) + Kd (x_c' - x'), the command x_c(t)
given with its rate. Its gains give a second-order loop of natural frequency w_b (the bandwidth, rad/s)
and damping ratio zeta on the inertia the joint sees with every other input held (`reflected_inertia`):
Kp = m w_b^2, Kd = 2 zeta m w_b. Its power counts as a source in the simulator's energy balance.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidArgument
from mechkit.forces import ForceElement, ForceState, Load
from mechkit.forces.coulomb import one_freedom_joint
from mechkit.mechanism import Mechanism

Command = Callable[[float], tuple[float, float]]
"""t (s) -> (commanded value (rad or m), its rate)."""


def reflected_inertia(mech: Mechanism, joint: str, q: np.ndarray | None = None) -> float:
    """The inertia a driven joint sees with every other input of the mechanism held: g^T M g, g the
    joint velocities of a unit rate of `joint` on the closed mechanism.

    Args:
        mech: the mechanism.
        joint: one of its inputs (`mech.spec.home` keys or actuators).
        q: (nq,) the configuration (default: home).

    Returns:
        The inertia (kg m^2 or kg).

    Raises:
        InvalidParameters: an unknown joint, or inputs that do not fix the motion.
    """
    q = mech.home_q if q is None else q
    names = list(dict.fromkeys([*mech.actuated, *mech.spec.home(mech.params)]))
    if joint not in names:
        names.append(joint)
    rates = np.zeros(len(names))
    rates[names.index(joint)] = 1.0
    g = mech.velocities(q, rates, names)
    return float(g @ pin.crba(mech.model, mech.model.createData(), q) @ g)


class PositionServo(ForceElement):
    """A position servo on one joint (see the module's docstring).

    Args:
        model: the tree's Pinocchio model.
        joint: the driven one-freedom joint.
        command: t -> (commanded value, rate).
        kp: position gain (N m/rad or N/m, > 0).
        kd: rate gain (N m s/rad or N s/m, >= 0).

    Raises:
        InvalidArgument: gains not finite, kp not > 0 or kd < 0.
        InvalidParameters: a joint that is not a one-freedom joint of the model.
    """

    role = "source"

    def __init__(self, model: pin.Model, joint: str, command: Command, kp: float, kd: float):
        if not (np.isfinite(kp) and np.isfinite(kd) and kp > 0 and kd >= 0):
            raise InvalidArgument("kp/kd", (kp, kd), "gains must be finite, kp > 0 and kd >= 0")
        self.index = one_freedom_joint(model, joint, "servo")
        self.q_index = model.idx_qs[model.getJointId(joint)]
        self.command, self.kp, self.kd = command, float(kp), float(kd)
        self.name = f"servo {joint}"

    @classmethod
    def with_bandwidth(
        cls, mech: Mechanism, joint: str, command: Command, bandwidth: float, damping: float = 0.7
    ) -> PositionServo:
        """A servo whose loop on the joint's reflected inertia has a given bandwidth and damping.

        Args:
            mech: the mechanism.
            joint: the driven joint.
            command: t -> (commanded value, rate).
            bandwidth: natural frequency of the loop (rad/s, > 0).
            damping: its damping ratio (> 0).

        Returns:
            The servo.

        Raises:
            InvalidArgument: a bandwidth or damping not finite and > 0.
        """
        if not (np.isfinite(bandwidth) and bandwidth > 0 and np.isfinite(damping) and damping > 0):
            raise InvalidArgument("bandwidth/damping", (bandwidth, damping), "must be finite and > 0")
        m = reflected_inertia(mech, joint)
        return cls(mech.model, joint, command, m * bandwidth**2, 2 * damping * m * bandwidth)

    def effort(self, t: float, q: np.ndarray, v: np.ndarray) -> float:
        """The servo's effort at a state.

        Args:
            t: time (s).
            q: (nq,) configuration.
            v: (nv,) velocities.

        Returns:
            Kp (x_c - x) + Kd (x_c' - x') (N m or N).
        """
        target, rate = self.command(t)
        return self.kp * (target - q[self.q_index]) + self.kd * (rate - v[self.index])

    def load(self, state: ForceState) -> Load:
        """The effort on the joint, and its power.

        Args:
            state: the state (`mechkit.forces.ForceState`).

        Returns:
            The `Load`: the effort at the joint's velocity index, its power effort * rate (W).
        """
        u = self.effort(state.t, state.q, state.v)
        tau = np.zeros(state.model.nv)
        tau[self.index] = u
        return Load(tau, None, u * float(state.v[self.index]))
