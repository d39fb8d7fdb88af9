"""Closure rows as world wrenches, for many samples at once.

Every closure row is a wrench W (6,) at the world origin: a position row t.(p_b - p_a) is the unit
force t at p_b, W = [t, p_b x t]; an alignment row (u fixed in frame_a, w in frame_b) is the pure
moment W = [0, w x u]. Its Jacobian is W^T J_world (Pinocchio's `data.J` after
`computeJointJacobians`: world axes, twists at the world origin) on the columns that move frame_b
minus those that move frame_a (a cached +1/-1/0 support mask), which is the exact derivative of the
row forms of `mechkit.core.closures`. The same wrenches, weighted by the row multipliers, are the cut
wrenches that frame_a's side exerts on frame_b's side.

Arrays carry a leading sample axis N; placements are (N, njoints, 4, 4) homogeneous matrices
(`data.oMi`, gathered by `mechkit.core.inverse`).
"""

from __future__ import annotations

import numpy as np

from mechkit.base.spatial import cross_batch
from mechkit.core.closures import ClosureRows, support_columns


class RowWrenches:
    """The rows of a `ClosureRows` set as world wrenches, evaluated for N samples at once.

    Each row carries two homogeneous 4-vectors in its joints' frames: on frame_a's joint the direction
    t or u (w = 0), on frame_b's joint frame_b's origin p_b (w = 1) for a position row or the direction
    w (w = 0) for an alignment row. In the world they give X_a and Y, and the row wrench is
    [X_a (position rows; 0 for alignment rows), Y x X_a]; position rows also carry frame_a's origin
    p_a (w = 1) for the residual. One gather and one product give them all (`evaluate`).

    Attributes:
        size: number of rows; ncuts: number of cuts.
        mask: (rows, nv) +1 on columns moving frame_b only, -1 on frame_a only, 0 elsewhere.
        row_sum: (ncuts, rows) 1 where a row belongs to a cut.
        joint_b, point_b: frame_b's joint and origin (homogeneous, in that joint's frame) per cut.
    """

    def __init__(self, rows: ClosureRows):
        model = rows.model
        self.size, self.ncuts = rows.size, len(rows.cuts)
        frames = model.frames
        joint_a = [frames[c.frame_a].parentJoint for c in rows.cuts]
        self.joint_b = np.array([frames[c.frame_b].parentJoint for c in rows.cuts], dtype=int)
        self.point_b = np.array([frames[c.frame_b].placement.homogeneous[:, 3] for c in rows.cuts]).reshape(-1, 4)
        row_a, row_b, is_force, cut_of_row, point_a = [], [], [], [], []
        for c, cut in enumerate(rows.cuts):
            Ma, Mb = frames[cut.frame_a].placement.homogeneous, frames[cut.frame_b].placement.homogeneous
            for t in cut.positions.T:
                row_a.append(Ma[:, :3] @ t), row_b.append(Mb[:, 3]), is_force.append(1.0), cut_of_row.append(c)
                point_a.append(Ma[:, 3])
            for u, w in cut.alignments:
                row_a.append(Ma[:, :3] @ u), row_b.append(Mb[:, :3] @ w), is_force.append(0.0), cut_of_row.append(c)
                point_a.append(np.zeros(4))
        self.cut_of_row = np.array(cut_of_row, dtype=int)
        self.row_joint_a = np.array(joint_a, dtype=int)[self.cut_of_row]
        self.row_joint_b = self.joint_b[self.cut_of_row]
        # one gather for `evaluate`: X_a, Y and p_a per row, then p_b per cut (homogeneous, in their joints)
        self._joints = np.concatenate([self.row_joint_a, self.row_joint_b, self.row_joint_a, self.joint_b])
        self._vectors = np.concatenate([np.reshape(x, (-1, 4)) for x in (row_a, row_b, point_a, self.point_b)])[..., None]
        self.is_force = np.array(is_force).reshape(-1, 1)
        self.row_sum = (self.cut_of_row[None, :] == np.arange(self.ncuts)[:, None]).astype(float)
        support = {j: support_columns(model, j) for j in set(joint_a) | set(self.joint_b.tolist())}
        cut_mask = np.array([support[b] - support[a] for a, b in zip(joint_a, self.joint_b.tolist())]).reshape(-1, model.nv)
        self.mask = cut_mask[self.cut_of_row] if self.size else np.zeros((0, model.nv))

    def evaluate(self, oMi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Row wrenches, residual norms and cut points from joint placements (N, njoints, 4, 4), in one gather.

        Returns:
            (N, rows, 6) row wrenches [force, moment about the world origin]; (N,) closure residual
            norms |e| (e = X_a . (p_b - p_a) for a position row, X_a . Y for an alignment row: the
            row forms of `mechkit.core.closures`, m for position rows); (N, ncuts, 3) frame_b origins p_b.
        """
        v = (oMi[:, self._joints, :3] @ self._vectors)[..., 0]
        r = self.size
        xa, y = v[:, :r], v[:, r:2 * r]
        residuals = np.sqrt(np.square((xa * (y - v[:, 2 * r:3 * r])).sum(axis=2)).sum(axis=1))
        return self._wrenches(xa, y), residuals, v[:, 3 * r:]

    def wrenches(self, oMi: np.ndarray) -> np.ndarray:
        """(N, rows, 6) row wrenches [force, moment about the world origin] from joint placements (N, njoints, 4, 4)."""
        r = self.size
        v = (oMi[:, self._joints[:2 * r], :3] @ self._vectors[:2 * r])[..., 0]
        return self._wrenches(v[:, :r], v[:, r:])

    def _wrenches(self, xa: np.ndarray, y: np.ndarray) -> np.ndarray:
        """(N, rows, 6) [X_a (position rows), Y x X_a] from the world vectors X_a and Y (N, rows, 3)."""
        return np.concatenate([xa * self.is_force, cross_batch(y, xa)], axis=-1)

    def jacobian(self, W: np.ndarray, J: np.ndarray) -> np.ndarray:
        """(N, rows, nv) closure Jacobian from the row wrenches (N, rows, 6) and `data.J` (N, 6, nv)."""
        return (W @ J) * self.mask

    def cut_wrenches(self, W: np.ndarray, lam: np.ndarray) -> np.ndarray:
        """(..., ncuts, 6) wrench of each cut [f, m about the world origin] from row wrenches (..., rows, 6)
        and multipliers (..., rows)."""
        return self.row_sum @ (W * lam[..., None])
