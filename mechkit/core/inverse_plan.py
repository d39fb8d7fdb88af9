"""What one sample of inverse dynamics builds once per closure data: maps, views and buffers.

As Pinocchio's model and data: what does not change between calls (the kernels' maps over every joint, the
actuation columns of [S^T, J^T]) is made on the first call and kept on the `ClosureData` (`inverse`), so a
call is Pinocchio's passes and a few products. Pinocchio 4.1 holds every joint placement [R | p] as 12
consecutive floats (R column by column, then p): that vector read as (4 njoints, 3) is every placement
transposed and stacked (`ClosureKernel.stacked_world`'s layout), so one product of a fixed map with it gives
the world vectors of the rows and of the full rows (the determinacy test's) together, with no gather.
"""

from __future__ import annotations

import numpy as np

from mechkit.core.model import ClosureData, ClosureModel
from mechkit.core.rank import squared_norm


class InversePlan:
    """The maps, views and buffers of `mechkit.core.inverse` for one closure model and one data of it.

    Args:
        cm: the closure model.
        cd: a data of it (its Pinocchio arrays are viewed, not copied).

    Attributes:
        cm: the model it was built for (a data used with another model gets a new plan).
        placements: (njoints, 4, 3) view of every joint's placement transposed, [R^T; p^T] (`ClosureData.oMi`).
        world: (rows' vectors + full rows' vectors, 4) buffer of the world vectors (`ClosureKernel.world`'s);
            rows_world, full_world: its two parts (views).
        origins: (njoints - 1, 3) view of the tree joints' origins in the world (`ClosureData.oMi`).
        rotations_t: (njoints - 1, 3, 3) view of the tree joints' rotations, transposed.
        forces: (njoints - 1, 2, 3) view of the tree joints' wrenches [f, m], local frames (`ClosureData.f`).
        statics: (nv, na + rows) buffer [S^T, J^T], S^T written once; full_statics: the same of the full rows
            (None where they are the rows).
        actuation_size: |S|_F^2.
    """

    def __init__(self, cm: ClosureModel, cd: ClosureData):
        self.cm, nj = cm, cm.model.njoints
        oMi = cd.oMi
        # every placement transposed, [R^T; p^T] (4, 3): Pinocchio's floats as they lie (one view, no copy)
        self.placements = np.lib.stride_tricks.as_strided(oMi, (nj, 4, 3), (oMi.strides[0], 24, 8), writeable=False)
        kernels = (cm.kernel,) if cm.spatial else (cm.kernel, cm.full_kernel)
        maps = [_joint_map(k, nj) for k in kernels]
        self._map = np.concatenate(maps)
        self.world = np.zeros((self._map.shape[0], 4))
        self.world[:, 3] = self._map.reshape(len(self._map), nj, 4)[:, :, 3].sum(axis=1)  # the vectors' w
        self._out = self.world[:, :3]
        rows = maps[0].shape[0]
        self.rows_world, self.full_world = self.world[:rows], self.world[rows - (rows if cm.spatial else 0) :]
        self.origins = oMi[1:, :, 3]
        self.rotations_t = oMi[1:, :, :3].transpose(0, 2, 1)
        self.forces = cd.f[1:].reshape(nj - 1, 2, 3)
        na = len(cm.actuated)
        self.statics = np.empty((cm.nv, na + cm.kernel.size))
        self.statics[:, :na] = cm.actuation.T
        self.actuation_size = squared_norm(cm.actuation)
        self.full_statics = None if cm.spatial else np.empty((cm.nv, na + cm.full_kernel.size))
        if self.full_statics is not None:
            self.full_statics[:, :na] = cm.actuation.T

    def fill_world(self) -> None:
        """The world vectors of the rows and full rows (`world`) from the placements Pinocchio holds now."""
        # (4 njoints, 3): a view where the placements lie 12 floats apart (pin 4.1), else a copy
        np.matmul(self._map, self.placements.reshape(-1, 3), out=self._out)


def _joint_map(k, nj: int) -> np.ndarray:
    """A kernel's map of the stacked used placements (`ClosureKernel.stacked_world`) over every joint's."""
    used = k.stacked_world(np.eye(4 * k.joints.size))
    out = np.zeros((used.shape[0], nj, 4))
    out[:, k.joints] = used.reshape(used.shape[0], k.joints.size, 4)
    return out.reshape(used.shape[0], 4 * nj)


def used_placements(cm: ClosureModel, P: np.ndarray) -> np.ndarray:
    """Homogeneous placements of the joints carrying cut frames.

    Args:
        cm: the closure model (its kernel's used joints).
        P: (N, nj, 3, 4) every joint's placement [R | p] in the world.

    Returns:
        (N, n_used, 4, 4) the used joints' homogeneous placements in the world.
    """
    G = np.zeros(P.shape[:1] + (cm.kernel.joints.size, 4, 4))
    G[..., :3, :], G[..., 3, 3] = P[:, cm.kernel.joints], 1.0
    return G


def plan(cm: ClosureModel, cd: ClosureData) -> InversePlan:
    """The data's plan for this model, made on first use (`ClosureData.inverse`).

    Args:
        cm: the closure model.
        cd: a data of it.

    Returns:
        The plan.
    """
    p = cd.inverse
    if p is None or p.cm is not cm:
        p = cd.inverse = InversePlan(cm, cd)
    return p
