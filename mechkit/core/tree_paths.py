"""Paths in the kinematic tree: the velocity columns that move a joint (the joints from the root to it)
and which cuts' frames lie in each joint's subtree, from the Pinocchio model's parents.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.core.cuts import CutRows


def support_columns(model: pin.Model, joint: int) -> np.ndarray:
    """The velocity columns that move a joint.

    Args:
        model: the Pinocchio model.
        joint: Pinocchio joint id (0, the universe: none).

    Returns:
        (nv,) 1.0 on the velocity columns of the joints from the root to `joint`, else 0.
    """
    out = np.zeros(model.nv)
    while joint > 0:
        jm = model.joints[joint]
        out[jm.idx_v : jm.idx_v + jm.nv] = 1.0
        joint = model.parents[joint]
    return out


def subtree_incidence(model: pin.Model, cuts: list[CutRows]) -> np.ndarray:
    """Which cuts' frames lie in each joint's subtree.

    Args:
        model: the Pinocchio model.
        cuts: the cuts, in order.

    Returns:
        (njoints, len(cuts)): +1 where joint i has frame_b's body of a cut in its subtree, -1 for
        frame_a's (0 for both or neither).
    """
    out = np.zeros((model.njoints, len(cuts)))
    for c, cut in enumerate(cuts):
        for sign, frame in ((1.0, cut.frame_b), (-1.0, cut.frame_a)):
            j = model.frames[frame].parentJoint
            while j > 0:
                out[j, c] += sign
                j = model.parents[j]
    return out
