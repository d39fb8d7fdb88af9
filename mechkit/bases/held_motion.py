"""A body held in the world while the base moves: the holding inputs along a base motion, and the motion
study they make (the motors' efforts and every joint's reaction, the carrier's accelerations included).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.bases.base_motion import BaseMotion, carried
from mechkit.bases.carrier import BASE_JOINTS
from mechkit.bases.holding import hold_pose
from mechkit.history.result import MotionResult
from mechkit.mechanism import Mechanism
from mechkit.motion import from_arrays, study


@dataclass(frozen=True)
class HeldMotion:
    """The holding inputs along a base motion and their study.

    Attributes:
        inputs: (N, k) the holding inputs (rad or m), in `names` order; names: the input joints.
        tilt: (N,) the tilt each sample's inputs leave (rad).
        study: the motion study (`mechkit.history.MotionResult`): efforts (the root joints' are the
            carrier's), reactions.
    """

    names: tuple[str, ...]
    inputs: np.ndarray
    tilt: np.ndarray
    study: MotionResult


def held_motion(mech: Mechanism, base: BaseMotion, frame: str, axis: tuple) -> HeldMotion:
    """Hold a body's axis along a base motion: the inputs at each sample (each from the last), their
    rates and accelerations from scipy's cubic spline, and the study of the whole motion.

    Args:
        mech: a mechanism on a moving base.
        base: the base's motion.
        frame: the held body's frame.
        axis: (body axis, world direction) kept (`hold_pose`; level: both (0, 0, 1)).

    Returns:
        The `HeldMotion`.

    Raises:
        InvalidArgument: a mechanism not on a moving base, a bad frame or axis.
        MotionFailed, SingularConfiguration: a sample the study cannot solve.
    """
    joints, start, rows, tilts = base.values[:, [0, 1, 2, 5, 4, 3]], None, [], []
    for pose in joints:
        held = hold_pose(mech, frame, axis=axis, base_pose=dict(zip(BASE_JOINTS, pose)), start=start)
        start = held.inputs
        rows.append(list(held.inputs.values()))
        tilts.append(held.tilt)
    names = tuple(start)
    law = from_arrays(mech, base.t, np.array(rows), names=names, source=f"held {frame}")
    return HeldMotion(names, np.array(rows), np.array(tilts), study(mech, carried(mech, base, law)))
