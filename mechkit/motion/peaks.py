"""Peak loads per joint along a motion, as a bearing is chosen: the largest force and moment and when,
each split into its axial part (along the joint axis) and its radial part (normal to it).

For a revolute joint the axial moment is the torque about the axis (the drive's, zero at a free
hinge) and the radial moment the tilting moment the bearing carries. Joints without a single axis
(spherical, Hooke, weld cuts) have NaN axial and radial parts.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from mechkit.history.result import MotionResult

if TYPE_CHECKING:
    import pandas as pd

#: Peak quantities, in table order: name -> (unit, description).
QUANTITIES = {
    "force": ("N", "|f|"),
    "axial_force": ("N", "|f . n|"),
    "radial_force": ("N", "|f - (f . n) n|"),
    "moment": ("N m", "|m|"),
    "axial_moment": ("N m", "|m . n|"),
    "radial_moment": ("N m", "|m - (m . n) n|"),
}


@dataclass(frozen=True)
class JointPeaks:
    """One joint's peaks: `values[k]` the largest of quantity k over the motion and `times[k]` (s)
    the first time it is reached (NaN for a quantity the joint has no axis for). `determinate`: every
    component of the reaction is fixed by statics at every sample (None: not tested); when False the
    peaks include minimum-norm values of indeterminate components (see `dynamics.JointReaction`)."""

    joint: str
    support: bool
    values: dict[str, float]
    times: dict[str, float]
    determinate: bool | None = None


def split(vectors: np.ndarray, axes: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A vector's magnitude and its parts along and across an axis.

    Args:
        vectors: vectors (..., 3).
        axes: unit axes (..., 3), broadcastable with them.

    Returns:
        (magnitude, |axial part|, |radial part|), each of shape (...).
    """
    along = np.einsum("...k,...k->...", vectors, axes)
    radial = vectors - along[..., None] * axes
    return np.linalg.norm(vectors, axis=-1), np.abs(along), np.linalg.norm(radial, axis=-1)


def load_histories(result: MotionResult) -> dict[str, np.ndarray]:
    """Quantity -> (N, n_joints) history of every `QUANTITIES` entry.

    Args:
        result: the study.

    Returns:
        Quantity -> (N, n_joints) history of every `QUANTITIES` entry (N, N m).
    """
    f, m, n = result.reactions[..., :3], result.reactions[..., 3:], result.axes
    return dict(zip(QUANTITIES, (*split(f, n), *split(m, n))))


def peaks(result: MotionResult) -> list[JointPeaks]:
    """Every joint's peaks, in the result's joint order.

    Args:
        result: the study.

    Returns:
        One `JointPeaks` per joint, in the result's joint order.
    """
    histories = load_histories(result)
    out = []
    for j, joint in enumerate(result.joints):
        values, times = {}, {}
        for name, h in histories.items():
            column = h[:, j]
            if np.all(np.isnan(column)):
                values[name] = times[name] = float("nan")
                continue
            k = int(np.nanargmax(column))
            values[name], times[name] = float(column[k]), float(result.t[k])
        determinate = None if result.determinate is None else bool(result.determinate[:, j].all())
        out.append(JointPeaks(joint, bool(result.supports[j]), values, times, determinate))
    return out


def peak_table(result: MotionResult) -> pd.DataFrame:
    """The peaks as a pandas DataFrame: one row per joint, columns `<quantity>` and `t_<quantity>`.

    Args:
        result: the study.

    Returns:
        The DataFrame.
    """
    from mechkit.history.result import pandas

    rows = [
        {
            "joint": p.joint,
            "support": p.support,
            "determinate": p.determinate,
            **{k: v for q in QUANTITIES for k, v in ((q, p.values[q]), (f"t_{q}", p.times[q]))},
        }
        for p in peaks(result)
    ]
    return pandas().DataFrame(rows).set_index("joint")
