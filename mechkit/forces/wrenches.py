"""External wrenches on bodies: a force through a point and a moment, given as functions of time.

`BodyWrench(model, joint, force, moment, point)`: the body moved by `joint` feels the world force
f(t) (N) through the point p, fixed in the body (m, in the joint's frame), and the world moment
m(t) (N m). Its power, f . v_p + m . omega, counts as a source in the energy balance.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters
from mechkit.forces.element import ForceElement, ForceState, Load, wrench_on_body

Vector = Callable[[float], np.ndarray] | np.ndarray | tuple[float, float, float]


def _of_time(what: str, value: Vector) -> Callable[[float], np.ndarray]:
    """A constant 3-vector or a function of time as a function of time (checked at t = 0)."""
    if callable(value):
        fn = value
    else:
        constant = np.asarray(value, dtype=float)
        fn = lambda t: constant
    first = np.asarray(fn(0.0), dtype=float)
    if first.shape != (3,) or not np.all(np.isfinite(first)):
        raise InvalidParameters(what, first, "needs three finite numbers (world frame)")
    return lambda t: np.asarray(fn(t), dtype=float)


class BodyWrench(ForceElement):
    """A world force through a body point plus a world moment, on the body of one joint.

    Args:
        model: the tree.
        joint: the joint whose body is loaded.
        force: (3,) N, world frame, or a function of t (s) giving it.
        moment: (3,) N m, world frame, or a function of t.
        point (ArrayLike): (3,) m, the force's point in the joint's frame (default: the joint origin).
        name: the element's name.

    Raises:
        InvalidParameters: an unknown joint, vectors not of three finite numbers.
    """

    role = "source"

    def __init__(
        self,
        model: pin.Model,
        joint: str,
        force: Vector = (0.0, 0.0, 0.0),
        moment: Vector = (0.0, 0.0, 0.0),
        point=(0.0, 0.0, 0.0),
        name: str | None = None,
    ):
        if not isinstance(joint, str) or not model.existJointName(joint):
            raise InvalidParameters("joint", joint, f"no such joint; joints: {list(model.names[1:])}")
        self.joint, self.id = joint, model.getJointId(joint)
        self.force, self.moment = _of_time("force", force), _of_time("moment", moment)
        self.point = np.asarray(point, dtype=float)
        if self.point.shape != (3,) or not np.all(np.isfinite(self.point)):
            raise InvalidParameters("point", point, "needs three finite numbers (m, joint frame)")
        self.name = name or f"wrench on {joint}"

    def load(self, state: ForceState) -> Load:
        """The wrench as the body's `fext` row, and its power.

        Args:
            state: the state (its t, world placements and velocities are read).

        Returns:
            The `Load`: body wrenches (njoints, 6) in `fext` convention (only the loaded body's row
            non-zero), no generalised forces, the power f . v_p + m . omega (W).
        """
        M = state.data.oMi[self.id]
        f, m = self.force(state.t), self.moment(state.t)
        p = M.act(self.point)
        out = np.zeros((state.model.njoints, 6))
        out[self.id] = wrench_on_body(state.model, state.data, self.id, f, m, p)
        twist = pin.getVelocity(state.model, state.data, self.id, pin.LOCAL_WORLD_ALIGNED)
        v_p = twist.linear + np.cross(twist.angular, p - M.translation)
        return Load(None, out, float(f @ v_p + m @ twist.angular))
