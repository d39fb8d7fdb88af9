"""Closure rows evaluated in numpy from one gather of joint placements, for one sample or many.

Every row of `mechkit.closures` reads three vectors of its cut's two joints, each a fixed homogeneous
4-vector mapped by a joint placement: X = R_a t (or u), the direction fixed in frame_a; Y = p_b (a
position row) or R_b w (an alignment row); Z = p_a (a position row) or 0. Then

- residual  e = X . (Y - Z);
- row wrench W = [f X, Y x X] (f = 1 for a position row, 0 for an alignment row), world axes, moment
  about the world origin, so that de/dt = W . (V_b - V_a) with V_j = [v_O, omega] the world twist of
  joint j at the world origin: the Jacobian is (W @ J_world) * mask (Pinocchio's `data.J` after
  `computeJointJacobians`; mask +1 on the columns moving only frame_b, -1 on those moving only frame_a);
- drift gamma = W . (A_b - A_a) + dW/dt . (V_b - V_a), A_j the spatial acceleration of joint j at zero
  joint accelerations (world, origin), so that d2e/dt2 = J a + gamma.

Arrays carry any leading sample axes; placements G are (..., n_used, 4, 4) for the joints in `joints`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin

if TYPE_CHECKING:
    from mechkit.closures import CutRows

#: Levi-Civita symbol as a (9, 3) matrix: (a outer b).reshape(9) @ LEVI_CIVITA = a x b.
LEVI_CIVITA = np.zeros((9, 3))
for _i, _j, _k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
    LEVI_CIVITA[3 * _i + _j, _k], LEVI_CIVITA[3 * _j + _i, _k] = 1.0, -1.0


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b on the last axis of two (..., 3) arrays of the same shape, as one matrix product."""
    outer = a[..., :, None] * b[..., None, :]
    return outer.reshape(*outer.shape[:-2], 9) @ LEVI_CIVITA


def support_columns(model: pin.Model, joint: int) -> np.ndarray:
    """(nv,) 1.0 on the velocity columns of the joints from the root to `joint` (0: none)."""
    out = np.zeros(model.nv)
    while joint > 0:
        jm = model.joints[joint]
        out[jm.idx_v:jm.idx_v + jm.nv] = 1.0
        joint = model.parents[joint]
    return out


class RowEvaluator:
    """The rows of a list of cuts as numpy maps of the placements of the joints they involve.

    Attributes:
        joints: (n_used,) ids of the joints carrying frame_a or frame_b of some cut.
        size: number of rows.
        mask: (rows, nv) Jacobian column signs (+1 frame_b only, -1 frame_a only, 0 both or none).
        support: (n_used, nv) 1 on the columns moving each used joint.
    """

    def __init__(self, model: pin.Model, cuts: list[CutRows]):
        frames = model.frames
        self.model = model
        self.joints = np.array(sorted({frames[f].parentJoint for c in cuts for f in (c.frame_a, c.frame_b)}), dtype=int)
        where = {int(j): k for k, j in enumerate(self.joints)}
        ia, ib, xz, y, f = [], [], [], [], []
        for cut in cuts:
            Ma, Mb = frames[cut.frame_a].placement.homogeneous, frames[cut.frame_b].placement.homogeneous
            ja, jb = where[frames[cut.frame_a].parentJoint], where[frames[cut.frame_b].parentJoint]
            for t in cut.positions.T:
                ia.append(ja), ib.append(jb), xz.append([Ma[:, :3] @ t, Ma[:, 3]]), y.append(Mb[:, 3]), f.append(1.0)
            for u, w in cut.alignments:
                ia.append(ja), ib.append(jb), xz.append([Ma[:, :3] @ u, np.zeros(4)]), y.append(Mb[:, :3] @ w), f.append(0.0)
        self.size = len(f)
        self._ia, self._ib = np.array(ia, dtype=int), np.array(ib, dtype=int)
        self._xz = np.array(xz, dtype=float).reshape(-1, 2, 4).transpose(0, 2, 1)  # (rows, 4, 2): X and Z
        self._y = np.array(y, dtype=float).reshape(-1, 4, 1)
        self._f = np.array(f).reshape(-1, 1)
        self.support = np.array([support_columns(model, int(j)) for j in self.joints]).reshape(-1, model.nv)
        self.mask = self.support[self._ib] - self.support[self._ia]

    def gather(self, data: pin.Data) -> np.ndarray:
        """(n_used, 4, 4) placements of the used joints from `data.oMi` (current after any forward pass)."""
        oMi = data.oMi.tolist()
        return np.array([oMi[j].np for j in self.joints]).reshape(-1, 4, 4)

    def vectors(self, G: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """X, Y, Z (..., rows, 3) of every row (world, m or unit) from placements (..., n_used, 4, 4)."""
        A = G[..., :3, :]
        xz = A[..., self._ia, :, :] @ self._xz
        return xz[..., 0], (A[..., self._ib, :, :] @ self._y)[..., 0], xz[..., 1]

    def residual(self, G: np.ndarray) -> np.ndarray:
        """(..., rows) residuals (m for position rows, dimensionless for alignment rows)."""
        x, y, z = self.vectors(G)
        return np.sum(x * (y - z), axis=-1)

    def wrenches(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """(..., rows, 6) row wrenches [force, moment about the world origin] from X, Y."""
        return np.concatenate([x * self._f, cross(y, x)], axis=-1)

    def evaluate(self, G: np.ndarray, J: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Residuals (..., rows) and Jacobian (..., rows, nv) from placements and `data.J` (..., 6, nv)."""
        x, y, z = self.vectors(G)
        return np.sum(x * (y - z), axis=-1), (self.wrenches(x, y) @ J) * self.mask

    def twists(self, J: np.ndarray, v: np.ndarray) -> np.ndarray:
        """(..., n_used, 6) world twists [v_O, omega] of the used joints from world Jacobian columns
        (..., 6, nv) times velocities (..., nv) (also: with `data.dJ`, the accelerations at a = 0)."""
        return np.swapaxes(J @ np.swapaxes(self.support * v[..., None, :], -1, -2), -1, -2)

    def world_twists(self, G: np.ndarray, local: np.ndarray) -> np.ndarray:
        """(..., n_used, 6) local joint motions [linear, angular] (..., n_used, 6) (Pinocchio's `data.v`,
        `data.a`) in world axes about the world origin."""
        R, p = G[..., :3, :3], G[..., :3, 3]
        angular = (R @ local[..., 3:, None])[..., 0]
        return np.concatenate([(R @ local[..., :3, None])[..., 0] + cross(p, angular), angular], axis=-1)

    def drift(self, G: np.ndarray, V: np.ndarray, A: np.ndarray) -> np.ndarray:
        """(..., rows) gamma with d2e/dt2 = J a + gamma, from the used joints' world twists V and
        accelerations at a = 0, A (..., n_used, 6)."""
        x, y, _ = self.vectors(G)
        Va, Vb = V[..., self._ia, :], V[..., self._ib, :]
        xdot = cross(Va[..., 3:], x)
        ydot = self._f * Vb[..., :3] + cross(Vb[..., 3:], y)
        Wdot = np.concatenate([xdot * self._f, cross(ydot, x) + cross(y, xdot)], axis=-1)
        Arel = A[..., self._ib, :] - A[..., self._ia, :]
        return np.sum(self.wrenches(x, y) * Arel + Wdot * (Vb - Va), axis=-1)
