"""Joint coordinates as values a user gives and reads: one number per one-freedom joint (rad or m).

Pinocchio gives a `continuous` (unbounded revolute) joint two coordinates (cos, sin); inputs,
outputs and reports treat it as an angle, converted here at the boundary.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters


def _unbounded(model: pin.Model, joint: int) -> bool:
    return model.nqs[joint] == 2 and model.nvs[joint] == 1


def set_value(model: pin.Model, q: np.ndarray, joint: int, value: float) -> None:
    """Write a one-freedom joint's value (rad or m) into q, in place (cos, sin for a continuous joint).

    Raises:
        InvalidParameters: the joint has more than one freedom (no single value sets it).
    """
    i = model.joints[joint].idx_q
    if model.nqs[joint] == 1:
        q[i] = value
    elif _unbounded(model, joint):
        q[i:i + 2] = np.cos(value), np.sin(value)
    else:
        raise InvalidParameters(model.names[joint], value, f"a {model.joints[joint].shortname()} joint has "
                                f"{model.nvs[joint]} freedoms: no single value sets it")


def value(model: pin.Model, q: np.ndarray, joint: int) -> float:
    """A one-freedom joint's value in q (rad or m; atan2(sin, cos) for a continuous joint)."""
    i = model.joints[joint].idx_q
    if _unbounded(model, joint):
        return float(np.arctan2(q[i + 1], q[i]))
    return float(q[i])


def values(model: pin.Model, q: np.ndarray) -> dict[str, float]:
    """Every one-freedom joint's value in q, by joint name."""
    return {model.names[j]: value(model, q, j) for j in range(1, model.njoints) if model.nvs[j] == 1}
