"""Springs, dampers and constant friction on loop-cut joints (the joints a `LoopClosure` closes, which have
no coordinate of the tree).

A revolute or prismatic cut's value x and rate are its frames' relative motion about (along) its axis
a, fixed in frame_a: for a revolute cut the angle of frame_b relative to frame_a about a, in
(-pi, pi], 0 where the frames are aligned (atan2(a . vee(R - R^T) / 2, (tr R - 1) / 2), R = R_a^T R_b);
for a prismatic cut a . (p_b - p_a). The same laws as at a tree joint (`JointSprings`, `CoulombFriction`)
give an effort that acts as a moment (a force along a) on frame_b's body and its opposite on frame_a's:
body wrenches, so that the joint reactions carry it.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters
from mechkit.core import CutRows, JointSpring
from mechkit.forces.coulomb import SPEED_THRESHOLD, smooth_sign
from mechkit.forces.element import ForceElement, ForceState, Load, wrench_on_body


class CutJoint:
    """The value, rate and effort of one revolute or prismatic loop-cut joint.

    Args:
        cut: the cut's rows (`ClosureModel.kernel.cuts` item: its closure and frame ids).

    Raises:
        InvalidParameters: a cut of another kind.
    """

    def __init__(self, cut: CutRows):
        self.name, self.kind = cut.closure.name, cut.closure.kind
        if self.kind not in ("revolute", "prismatic"):
            raise InvalidParameters("cut joint", self.name, f"a {self.kind} cut: revolute and prismatic cuts only")
        self.frame_a, self.frame_b = cut.frame_a, cut.frame_b
        self.axis = np.asarray(cut.closure.axis, dtype=float)

    def value(self, data: pin.Data) -> float:
        """The cut's value (rad or m; see the module docstring).

        Args:
            data: the model's data with its frame placements (`updateFramePlacements`).

        Returns:
            x (rad in (-pi, pi], or m).
        """
        Ma, Mb = data.oMf[self.frame_a], data.oMf[self.frame_b]
        if self.kind == "prismatic":
            return float((Ma.rotation @ self.axis) @ (Mb.translation - Ma.translation))
        R = Ma.rotation.T @ Mb.rotation
        sine = 0.5 * float(self.axis @ np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]))
        return float(np.arctan2(sine, 0.5 * (np.trace(R) - 1.0)))

    def rate(self, model: pin.Model, data: pin.Data) -> float:
        """The cut's rate (rad/s or m/s).

        Args:
            model: the tree's Pinocchio model.
            data: its data after `forwardKinematics(q, v)` and `updateFramePlacements`.

        Returns:
            dx/dt: a . (w_b - w_a) (revolute) or a . (v_b - v_a) at frame_b's origin (prismatic), world a.
        """
        axis = data.oMf[self.frame_a].rotation @ self.axis
        va = pin.getFrameVelocity(model, data, self.frame_a, pin.LOCAL_WORLD_ALIGNED)
        vb = pin.getFrameVelocity(model, data, self.frame_b, pin.LOCAL_WORLD_ALIGNED)
        if self.kind == "revolute":
            return float(axis @ (vb.angular - va.angular))
        arm = data.oMf[self.frame_b].translation - data.oMf[self.frame_a].translation
        return float(axis @ (vb.linear - va.linear - np.cross(va.angular, arm)))

    def wrenches(self, model: pin.Model, data: pin.Data, effort: float, out: np.ndarray) -> None:
        """Add the cut's effort to the bodies' wrenches: on frame_b's body, its opposite on frame_a's.

        Args:
            model: the tree's Pinocchio model.
            data: its data with world placements (`oMi`, `oMf`).
            effort: the effort (N m about the axis, or N along it).
            out: (njoints, 6) wrenches (`fext` convention), added to in place.
        """
        axis = data.oMf[self.frame_a].rotation @ self.axis
        point = data.oMf[self.frame_b].translation
        zero = np.zeros(3)
        for frame, sign in ((self.frame_b, 1.0), (self.frame_a, -1.0)):
            joint = model.frames[frame].parentJoint
            if not joint:
                continue
            f, m = (zero, sign * effort * axis) if self.kind == "revolute" else (sign * effort * axis, zero)
            out[joint] += wrench_on_body(model, data, joint, f, m, point)


def cut_joints(cuts: Sequence, names: Iterable[str], what: str) -> list[CutJoint]:
    """The `CutJoint` of each named cut.

    Args:
        cuts: the cuts' rows (`ClosureModel.kernel.cuts`).
        names: the cut joints' names (iterable of str).
        what: what asks (named in the error).

    Returns:
        One `CutJoint` per name, in order.

    Raises:
        InvalidParameters: a name that is no cut joint, a cut neither revolute nor prismatic.
    """
    by_name = {c.closure.name: c for c in cuts}
    out = []
    for name in names:
        if name not in by_name:
            raise InvalidParameters(what, name, f"no such cut joint; cut joints: {list(by_name)}")
        out.append(CutJoint(by_name[name]))
    return out


class CutJointSprings(ForceElement):
    """Springs and dampers on loop-cut joints: effort = preload - stiffness (x - reference) - damping dx/dt.

    Args:
        model: the tree's Pinocchio model.
        cuts: the cuts' rows (`ClosureModel.kernel.cuts`).
        springs: `JointSpring` records naming cut joints.
        name: the element's name.

    Raises:
        InvalidParameters: a joint that is no revolute or prismatic cut.
    """

    def __init__(self, model: pin.Model, cuts: Sequence, springs: Sequence[JointSpring], name: str = "cut springs"):
        self.name, self.springs = name, tuple(springs)
        self.joints = cut_joints(cuts, [s.joint for s in self.springs], "spring")
        self.role = "dissipative" if any(s.damping for s in self.springs) else "conservative"

    def load(self, state: ForceState) -> Load:
        """The springs' and dampers' efforts as body wrenches, and the dampers' power.

        Args:
            state: the state, its kinematics computed.

        Returns:
            The `Load`: no generalised forces, body wrenches (njoints, 6), the dampers' power (W, <= 0).
        """
        model, data = state.model, state.data
        out = np.zeros((model.njoints, 6))
        power = 0.0
        for joint, s in zip(self.joints, self.springs):
            rate = joint.rate(model, data)
            effort = s.preload - s.stiffness * (joint.value(data) - s.reference) - s.damping * rate
            joint.wrenches(model, data, effort, out)
            power -= s.damping * rate**2
        return Load(None, out, power)

    def energy(self, model: pin.Model, data: pin.Data, q: np.ndarray) -> float:
        """The springs' potential: sum of stiffness (x - reference)^2 / 2 - preload (x - reference).

        Args:
            model: the tree's Pinocchio model.
            data: its data after `forwardKinematics(q)` (frames are placed here).
            q: (nq,) configuration (unused: `data` has it).

        Returns:
            The potential energy (J).
        """
        pin.updateFramePlacements(model, data)
        total = 0.0
        for joint, s in zip(self.joints, self.springs):
            dx = joint.value(data) - s.reference
            total += 0.5 * s.stiffness * dx**2 - s.preload * dx
        return total


class CutJointFriction(ForceElement):
    """Constant-size friction on loop-cut joints: effort = -F tanh(rate / threshold) (`CoulombFriction`'s law).

    Args:
        model: the tree's Pinocchio model.
        cuts: the cuts' rows (`ClosureModel.kernel.cuts`).
        sizes: cut joint name -> F (N m or N, >= 0).
        threshold: the regularisation's rate (rad/s or m/s, > 0).
        name: the element's name.

    Raises:
        InvalidParameters: a joint that is no revolute or prismatic cut, a negative size, a threshold <= 0.
    """

    role = "dissipative"
    friction = True

    def __init__(
        self,
        model: pin.Model,
        cuts: Sequence,
        sizes: Mapping[str, float],
        threshold: float = SPEED_THRESHOLD,
        name: str = "cut friction",
    ):
        if not threshold > 0:
            raise InvalidParameters("threshold", threshold, "the friction's speed threshold must be > 0")
        self.name, self.threshold, self.sizes = name, float(threshold), dict(sizes)
        for joint, size in self.sizes.items():
            if not size >= 0:
                raise InvalidParameters(f"friction on {joint}", size, "must be >= 0")
        self.joints = cut_joints(cuts, self.sizes, "friction")

    def load(self, state: ForceState) -> Load:
        """The friction efforts as body wrenches, and their power.

        Args:
            state: the state, its kinematics computed.

        Returns:
            The `Load`: no generalised forces, body wrenches (njoints, 6), the power (W, <= 0).
        """
        model, data = state.model, state.data
        out = np.zeros((model.njoints, 6))
        power = 0.0
        for joint, size in zip(self.joints, self.sizes.values()):
            rate = joint.rate(model, data)
            effort = -size * float(smooth_sign(rate, self.threshold))
            joint.wrenches(model, data, effort, out)
            power += effort * rate
        return Load(None, out, power)


class CutJointEffort(ForceElement):
    """A given effort on one loop-cut joint (a torque about a revolute cut's axis, a force along a prismatic
    cut's), constant or a function of time: a source, its power effort x rate.

    Args:
        model: the tree's Pinocchio model (unused: the cut's frames are its).
        cuts: the cuts' rows (`ClosureModel.kernel.cuts`).
        joint: the cut joint's name.
        effort: N m or N, or a function of t (s) giving it.
        name: the element's name (default "effort on <joint>").

    Raises:
        InvalidParameters: a joint that is no revolute or prismatic cut.
    """

    role = "source"

    def __init__(
        self, model: pin.Model, cuts: Sequence, joint: str, effort: float | Callable[[float], float], name: str = ""
    ):
        self.joint = cut_joints(cuts, [joint], "effort")[0]
        self.effort = effort if callable(effort) else (lambda t, e=float(effort): e)
        self.name = name or f"effort on {joint}"

    def load(self, state: ForceState) -> Load:
        """The effort as body wrenches, and its power.

        Args:
            state: the state, its kinematics computed (its t is read).

        Returns:
            The `Load`: no generalised forces, body wrenches (njoints, 6), the power effort x rate (W).
        """
        out = np.zeros((state.model.njoints, 6))
        effort = float(self.effort(state.t))
        self.joint.wrenches(state.model, state.data, effort, out)
        return Load(None, out, effort * self.joint.rate(state.model, state.data))
