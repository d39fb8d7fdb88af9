"""Unit axes (world frame) of every joint of a mechanism along a motion: what the reaction tables split
into axial and radial parts. Takes any object with a mechanism's `model`, `home_q`, `closure_model` and
`cuts` (the motion studies' and the simulator's)."""

from __future__ import annotations

import numpy as np
import pinocchio as pin


class JointAxes:
    """Unit axes (world frame) of every joint: tree joints in model order, then the cuts (`mech.cuts`).

    Tree joints of one degree of freedom: the rotation axis (revolute) or the sliding direction
    (prismatic), the angular or linear part of the joint's world Jacobian column. Cut joints: the
    declared axis of a revolute or prismatic closure, in frame_a's frame. Other joints (spherical,
    Hooke, weld) have no single axis: NaN.
    """

    def __init__(self, mech):
        model = mech.model
        data = model.createData()
        pin.forwardKinematics(model, data, mech.home_q)
        self.column = np.zeros(model.njoints - 1, dtype=int)  # velocity column of the joint
        self.angular = np.zeros(model.njoints - 1, dtype=bool)  # its axis in the angular part
        self.single = np.zeros(model.njoints - 1, dtype=bool)  # one degree of freedom
        for j in range(1, model.njoints):
            if model.joints[j].nv == 1:
                S = np.asarray(data.joints[j].S).reshape(6)
                self.column[j - 1], self.angular[j - 1], self.single[j - 1] = (
                    model.joints[j].idx_v,
                    np.linalg.norm(S[3:]) > 0,
                    True,
                )
        used = mech.closure_model.kernel.joints
        frames = model.frames
        self.cut_joint = np.array(
            [int(np.searchsorted(used, frames[c.frame_a].parentJoint)) for c in mech.cuts], dtype=int
        )
        self.cut_axis = np.array(
            [
                frames[c.frame_a].placement.rotation @ np.asarray(c.closure.axis, dtype=float)
                if c.closure.kind in ("revolute", "prismatic")
                else np.full(3, np.nan)
                for c in mech.cuts
            ]
        ).reshape(-1, 3)

    def world(self, J: np.ndarray, G: np.ndarray) -> np.ndarray:
        """World joint axes of N samples.

        Args:
            J: world joint Jacobians (N, 6, nv).
            G: the rows' used joint placements (N, n_used, 4, 4) (`core.kinematic_pass`).

        Returns:
            Unit axes (N, n_joints, 3), world frame; NaN for a joint of several freedoms.
        """
        cols = J[:, :, self.column]  # (N, 6, n_tree)
        tree = np.where(self.angular[None, :, None], np.swapaxes(cols[:, 3:], 1, 2), np.swapaxes(cols[:, :3], 1, 2))
        tree = tree / np.linalg.norm(tree, axis=-1, keepdims=True)
        tree[:, ~self.single] = np.nan
        cuts = (G[:, self.cut_joint, :3, :3] @ self.cut_axis[..., None])[..., 0]
        return np.concatenate([tree, cuts], axis=1)
