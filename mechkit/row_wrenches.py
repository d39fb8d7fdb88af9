"""Closure rows as world wrenches, for many samples at once.

Every closure row is a wrench W (6,) at the world origin: a position row t.(p_b - p_a) is the unit
force t at p_b, W = [t, p_b x t]; an alignment row (u fixed in frame_a, w in frame_b) is the pure
moment W = [0, w x u]. Its Jacobian is W^T J_world (Pinocchio's `data.J` after
`computeJointJacobians`: world axes, twists at the world origin) on the columns that move frame_b
minus those that move frame_a (a cached +1/-1/0 support mask), which is the exact derivative of the
row forms of `mechkit.closures`. The same wrenches, weighted by the row multipliers, are the cut
wrenches that frame_a's side exerts on frame_b's side.

Arrays carry a leading sample axis N; placements are (N, njoints, 4, 4) homogeneous matrices
(`placements` reads them from a Pinocchio data).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.closures import ClosureRows

#: Levi-Civita symbol as a (9, 3) matrix: (a outer b).reshape(9) @ LEVI_CIVITA = a x b.
LEVI_CIVITA = np.zeros((9, 3))
for _i, _j, _k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
    LEVI_CIVITA[3 * _i + _j, _k], LEVI_CIVITA[3 * _j + _i, _k] = 1.0, -1.0


def cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b on the last axis of two broadcastable (..., 3) arrays, as one matrix product."""
    outer = a[..., :, None] * b[..., None, :]
    return outer.reshape(*outer.shape[:-2], 9) @ LEVI_CIVITA


def placements(data: pin.Data) -> np.ndarray:
    """(njoints, 4, 4) homogeneous joint placements data.oMi."""
    return np.array([M.np for M in data.oMi.tolist()])


def support_columns(model: pin.Model, joint: int) -> np.ndarray:
    """(nv,) 1.0 on the velocity columns of the joints from the root to `joint` (0: none)."""
    out = np.zeros(model.nv)
    while joint > 0:
        jm = model.joints[joint]
        out[jm.idx_v:jm.idx_v + jm.nv] = 1.0
        joint = model.parents[joint]
    return out


class RowWrenches:
    """The rows of a `ClosureRows` set as world wrenches, evaluated for N samples at once.

    Attributes:
        size: number of rows.
        ncuts: number of cuts.
        mask: (rows, nv) +1 on columns moving frame_b only, -1 on frame_a only, 0 elsewhere.
        cut_of_row: (rows,) the cut of each row.
        row_sum: (ncuts, rows) 1 where a row belongs to a cut.
    """

    def __init__(self, rows: ClosureRows):
        model = rows.model
        self.size, self.ncuts = rows.size, len(rows.cuts)
        self.joint_a = np.array([model.frames[c.frame_a].parentJoint for c in rows.cuts], dtype=int)
        self.joint_b = np.array([model.frames[c.frame_b].parentJoint for c in rows.cuts], dtype=int)
        self.frame_a = np.array([model.frames[c.frame_a].placement.homogeneous for c in rows.cuts]).reshape(-1, 4, 4)
        self.frame_b = np.array([model.frames[c.frame_b].placement.homogeneous for c in rows.cuts]).reshape(-1, 4, 4)
        pos_cut, pos_t, al_cut, al_u, al_w, kind = [], [], [], [], [], []
        cut_of_row = []
        for c, cut in enumerate(rows.cuts):
            for t in cut.positions.T:
                pos_cut.append(c), pos_t.append(t), kind.append(0), cut_of_row.append(c)
            for u, w in cut.alignments:
                al_cut.append(c), al_u.append(u), al_w.append(w), kind.append(1), cut_of_row.append(c)
        kind = np.array(kind, dtype=int)
        self.pos_rows, self.align_rows = np.flatnonzero(kind == 0), np.flatnonzero(kind == 1)
        self.pos_cut, self.align_cut = np.array(pos_cut, dtype=int), np.array(al_cut, dtype=int)
        self.pos_t = np.array(pos_t, dtype=float).reshape(-1, 3)
        self.align_u = np.array(al_u, dtype=float).reshape(-1, 3)
        self.align_w = np.array(al_w, dtype=float).reshape(-1, 3)
        self.cut_of_row = np.array(cut_of_row, dtype=int)
        self.row_sum = (self.cut_of_row[None, :] == np.arange(self.ncuts)[:, None]).astype(float)
        support = {j: support_columns(model, j) for j in set(self.joint_a.tolist()) | set(self.joint_b.tolist())}
        cut_mask = np.array([support[b] - support[a] for a, b in zip(self.joint_a.tolist(), self.joint_b.tolist())]).reshape(-1, model.nv)
        self.mask = cut_mask[self.cut_of_row] if self.size else np.zeros((0, model.nv))

    def cut_frames(self, oMi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(N, ncuts, 4, 4) world placements of frame_a and frame_b from joint placements (N, njoints, 4, 4)."""
        return oMi[:, self.joint_a] @ self.frame_a, oMi[:, self.joint_b] @ self.frame_b

    def wrenches(self, oMa: np.ndarray, oMb: np.ndarray) -> np.ndarray:
        """(N, rows, 6) row wrenches [force, moment about the world origin] from the cut frames."""
        n = oMa.shape[0]
        out = np.zeros((n, self.size, 6))
        if self.pos_rows.size:
            t = np.einsum("nrij,rj->nri", oMa[:, self.pos_cut, :3, :3], self.pos_t)
            out[:, self.pos_rows, :3] = t
            out[:, self.pos_rows, 3:] = cross3(oMb[..., :3, 3][:, self.pos_cut], t)
        if self.align_rows.size:
            u = np.einsum("nrij,rj->nri", oMa[:, self.align_cut, :3, :3], self.align_u)
            w = np.einsum("nrij,rj->nri", oMb[:, self.align_cut, :3, :3], self.align_w)
            out[:, self.align_rows, 3:] = cross3(w, u)
        return out

    def jacobian(self, W: np.ndarray, J: np.ndarray) -> np.ndarray:
        """(N, rows, nv) closure Jacobian from the row wrenches (N, rows, 6) and `data.J` (N, 6, nv)."""
        return (W @ J) * self.mask

    def cut_wrenches(self, W: np.ndarray, lam: np.ndarray) -> np.ndarray:
        """(N, ncuts, 6) wrench of each cut [f, m about the world origin] from multipliers (N, rows)."""
        return self.row_sum @ (W * lam[..., None])


def shift_moment(wrench: np.ndarray, point: np.ndarray) -> np.ndarray:
    """Wrenches [f, m about the origin] (..., 6) re-expressed about `point` (..., 3): m - point x f."""
    out = wrench.copy()
    out[..., 3:] -= cross3(point, wrench[..., :3])
    return out
