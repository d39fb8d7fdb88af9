"""Numbers as XML attribute text, shared by the MJCF and Extended URDF writers."""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
import pinocchio as pin


def numbers(values: float | Iterable[float] | np.ndarray) -> str:
    """Values as XML attribute text at full precision (`repr` of each float), e.g. "0.1 0.0 -9.81".

    Args:
        values: a number or numbers (any shape, flattened).

    Returns:
        The text.
    """
    return " ".join(repr(float(x)) for x in np.ravel(np.asarray(values, dtype=float)))


def quat_wxyz(rotation: np.ndarray) -> np.ndarray:
    """The unit quaternion of a rotation matrix, in MuJoCo's order.

    Args:
        rotation: a rotation matrix (3, 3).

    Returns:
        (w, x, y, z), shape (4,).
    """
    x, y, z, w = pin.Quaternion(rotation).coeffs()
    return np.array([w, x, y, z])
