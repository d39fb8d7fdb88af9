"""Joint values as a user gives and reads them, for every Pinocchio joint type.

Pinocchio's configuration q has nq coordinates and its velocity nv; they differ for some joints.
A user sees one value per velocity coordinate (`size(joint) == nv`), converted here at the boundary:

| joint | q (Pinocchio) | value |
|---|---|---|
| revolute, prismatic, helical (any axis) | angle or distance | the same (rad or m) |
| continuous (unbounded revolute) | (cos, sin) | the angle (rad) |
| spherical (ball) | unit quaternion (x, y, z, w) | rotation vector (3,), rad, of the child in the parent joint frame |
| free-flyer | position (3,), quaternion | position (m) and rotation vector (rad), (6,) |
| planar | (x, y, cos, sin) | (x, y, angle) (m, m, rad) |
| spherical ZYX, translation, universal | as many coordinates as freedoms | the same |

Velocities and accelerations need no conversion: they are Pinocchio's (a ball joint's angular
velocity in its child frame, a free-flyer's twist in its body frame).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters

#: Joint types whose value is their quaternion turned into a rotation vector (after `_LEADING` coordinates).
_QUATERNION = {"JointModelSpherical": 0, "JointModelFreeFlyer": 3}


def size(model: pin.Model, joint: int) -> int:
    """Number of values of a joint.

    Args:
        model: the Pinocchio model.
        joint: Pinocchio joint id.

    Returns:
        The joint's velocity dimension nv.
    """
    return int(model.nvs[joint])


def _kind(model: pin.Model, joint: int) -> str:
    return model.joints[joint].shortname()


def _unbounded(model: pin.Model, joint: int) -> bool:
    """A continuous revolute (cos, sin) joint or the angle of a planar joint."""
    return model.nqs[joint] == 2 and model.nvs[joint] == 1


def set_value(model: pin.Model, q: np.ndarray, joint: int, value: float | np.ndarray) -> None:
    """Write a joint's value (see the module table) into q, in place.

    Args:
        model: the Pinocchio model.
        q: (nq,) configuration, changed in place.
        joint: Pinocchio joint id.
        value: a number for a one-freedom joint, else an array of `size(model, joint)` numbers.

    Raises:
        InvalidParameters: a value of the wrong size, or a joint type this module does not know.
    """
    i, nq, nv = model.joints[joint].idx_q, int(model.nqs[joint]), size(model, joint)
    x = np.atleast_1d(np.asarray(value, dtype=float))
    if x.shape != (nv,):
        raise InvalidParameters(
            model.names[joint],
            value,
            f"a {_kind(model, joint)} joint takes {nv} value(s) "
            f"({'rad or m' if nv == 1 else 'see mechkit.core.joints'}), got shape {x.shape}",
        )
    kind = _kind(model, joint)
    if nq == nv:
        q[i : i + nq] = x
    elif _unbounded(model, joint):
        q[i : i + 2] = np.cos(x[0]), np.sin(x[0])
    elif kind in _QUATERNION:
        lead = _QUATERNION[kind]
        q[i : i + lead] = x[:lead]
        q[i + lead : i + nq] = pin.Quaternion(pin.exp3(x[lead:])).coeffs()
    elif kind == "JointModelPlanar":
        q[i : i + 4] = x[0], x[1], np.cos(x[2]), np.sin(x[2])
    else:
        raise InvalidParameters(model.names[joint], value, f"values of a {kind} joint are not supported")


def value(model: pin.Model, q: np.ndarray, joint: int) -> float | np.ndarray:
    """A joint's value in q (see the module table).

    Args:
        model: the Pinocchio model.
        q: (nq,) configuration.
        joint: Pinocchio joint id.

    Returns:
        A float for a one-freedom joint, else an array of `size(model, joint)` values (rad or m).

    Raises:
        InvalidParameters: a joint type this module does not know.
    """
    i, nq, nv = model.joints[joint].idx_q, int(model.nqs[joint]), size(model, joint)
    kind = _kind(model, joint)
    if nq == nv:
        out = np.array(q[i : i + nq], dtype=float)
    elif _unbounded(model, joint):
        return float(np.arctan2(q[i + 1], q[i]))
    elif kind in _QUATERNION:
        lead = _QUATERNION[kind]
        quat = pin.Quaternion(np.asarray(q[i + lead : i + nq], dtype=float)).normalized()
        out = np.concatenate([q[i : i + lead], pin.log3(quat.matrix())])
    elif kind == "JointModelPlanar":
        out = np.array([q[i], q[i + 1], np.arctan2(q[i + 3], q[i + 2])])
    else:
        raise InvalidParameters(model.names[joint], kind, "values of this joint type are not supported")
    return float(out[0]) if nv == 1 else out


def values(model: pin.Model, q: np.ndarray) -> dict[str, float | np.ndarray]:
    """Every joint's value in q, by joint name.

    Args:
        model: the Pinocchio model.
        q: (nq,) configuration.

    Returns:
        Joint name -> value (`value`), in model order, the universe left out.
    """
    return {model.names[j]: value(model, q, j) for j in range(1, model.njoints)}


def velocity_indices(model: pin.Model, joint: int) -> np.ndarray:
    """Indices of a joint's velocity coordinates in v.

    Args:
        model: the Pinocchio model.
        joint: Pinocchio joint id.

    Returns:
        (nv_joint,) the indices, ascending.
    """
    start = model.joints[joint].idx_v
    return np.arange(start, start + size(model, joint))


def is_one_freedom(model: pin.Model, joint: int) -> bool:
    """Whether a joint has one velocity coordinate (revolute, prismatic, continuous, helical).

    Args:
        model: the Pinocchio model.
        joint: Pinocchio joint id.

    Returns:
        True for a joint with nv = 1.
    """
    return size(model, joint) == 1
