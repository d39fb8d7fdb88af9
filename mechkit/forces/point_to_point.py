"""Point-to-point elements: a spring, a damper and a force acting along the line between two body points
(a vibration isolator's strut, a gas spring, an actuator modelled as a force, MuJoCo's spatial tendon
between two sites).

With L the distance between the points (m) and L_dot its rate (m/s), the force along the line,
positive where it pushes the points apart (MuJoCo's tendon convention), is

    F = -stiffness (L - free_length) - damping L_dot + force + law(L, L_dot, t).

It acts on body b as F u through point b and on body a as -F u through point a, u the unit vector from
a to b: body wrenches, so that its generalised forces are J^T f from one kinematics pass and the
joint reactions of the bodies it acts on carry it. In the energy balance the spring and the constant
force are conservative (potential stiffness (L - free_length)^2 / 2 - force (L - free_length)), the
damper dissipates -damping L_dot^2, and the law's power law L_dot counts as a source.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.core import PointToPoint
from mechkit.forces.element import ForceElement, ForceState, Load, wrench_on_body

#: Distance (m) under which the two points count as one and the line of action is undefined (ours).
COINCIDENT = 1e-12


def _anchor(model: pin.Model, frame: str, point, where: str) -> tuple[int, np.ndarray]:
    """(joint id, the point in that joint's frame) of a point fixed in a named frame."""
    if not isinstance(frame, str) or not model.existFrame(frame):
        raise InvalidParameters(where, frame, f"no such frame; frames: {[f.name for f in model.frames]}")
    f = model.frames[model.getFrameId(frame)]
    return int(f.parentJoint), f.placement.act(np.asarray(point, dtype=float))


class PointToPointForce(ForceElement):
    """One `PointToPoint` element on a model.

    Args:
        model: the tree's Pinocchio model.
        element: the element's data.

    Raises:
        InvalidParameters: a frame the model does not have.
    """

    def __init__(self, model: pin.Model, element: PointToPoint):
        self.element, self.name = element, element.name
        self.role = "source" if element.law else ("dissipative" if element.damping else "conservative")
        self._a = _anchor(model, element.frame_a, element.point_a, f"{element.name} frame_a")
        self._b = _anchor(model, element.frame_b, element.point_b, f"{element.name} frame_b")

    def _point(self, data: pin.Data, anchor: tuple[int, np.ndarray]) -> np.ndarray:
        joint, local = anchor
        return data.oMi[joint].act(local)

    def _velocity(self, data: pin.Data, anchor: tuple[int, np.ndarray]) -> np.ndarray:
        joint, local = anchor
        twist = data.v[joint]  # the joint body's twist, its frame, about its origin
        return data.oMi[joint].rotation @ (twist.linear + np.cross(twist.angular, local))

    def geometry(self, data: pin.Data) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """The points and the line between them.

        Args:
            data: the model's data after `forwardKinematics(q)` (world placements `oMi`).

        Returns:
            (point a (3,), point b (3,), unit vector a -> b (3,), length L (m)); world frame.

        Raises:
            SingularConfiguration: the points coincide (no line of action).
        """
        pa, pb = self._point(data, self._a), self._point(data, self._b)
        length = float(np.linalg.norm(pb - pa))
        if length < COINCIDENT:
            raise SingularConfiguration(
                math.inf, f"the points of {self.name!r} coincide: its line of action is undefined"
            )
        return pa, pb, (pb - pa) / length, length

    def load(self, state: ForceState) -> Load:
        """The force on both bodies as their `fext` rows, and the non-conservative power.

        Args:
            state: the state (world placements and joint velocities are read).

        Returns:
            The `Load`: no generalised forces; body wrenches (njoints, 6), `fext` convention; the power
            (W) of the damper (<= 0) or of the law.

        Raises:
            SingularConfiguration: the points coincide.
            InvalidParameters: the law gives a force that is not finite.
        """
        e, model, data = self.element, state.model, state.data
        pa, pb, u, length = self.geometry(data)
        rate = float(u @ (self._velocity(data, self._b) - self._velocity(data, self._a)))
        extra = float(e.law(length, rate, state.t)) if e.law else -e.damping * rate
        if not math.isfinite(extra):
            raise InvalidParameters(f"{self.name} law", extra, f"gave a force that is not finite at L = {length:.6g} m")
        F = -e.stiffness * (length - e.free_length) + e.force + extra
        out = np.zeros((model.njoints, 6))
        zero = np.zeros(3)
        for (joint, _), point, sign in ((self._b, pb, 1.0), (self._a, pa, -1.0)):
            if joint:
                out[joint] += wrench_on_body(model, data, joint, sign * F * u, zero, point)
        return Load(None, out, extra * rate)

    def energy(self, model: pin.Model, data: pin.Data, q: np.ndarray) -> float:
        """The spring's and the constant force's potential at q.

        Args:
            model: the tree's Pinocchio model (unused: the points are resolved already).
            data: its data after `forwardKinematics(q)`.
            q: (nq,) configuration (unused: `data` has it).

        Returns:
            stiffness (L - free_length)^2 / 2 - force (L - free_length) (J).

        Raises:
            SingularConfiguration: the points coincide.
        """
        e = self.element
        stretch = self.geometry(data)[3] - e.free_length
        return 0.5 * e.stiffness * stretch**2 - e.force * stretch


def point_to_point(model: pin.Model, elements: Sequence[PointToPoint]) -> list[PointToPointForce]:
    """Force elements of `PointToPoint` records.

    Args:
        model: the tree's Pinocchio model.
        elements: the records (a sequence of `PointToPoint`).

    Returns:
        One `PointToPointForce` each.

    Raises:
        InvalidParameters: a frame the model does not have.
    """
    return [PointToPointForce(model, e) for e in elements]
