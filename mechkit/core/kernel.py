"""The closure kernel: every constraint row's residual, Jacobian, acceleration drift and wrench, and
what the row multipliers put on every joint, for one sample or N, from one gather of joint placements.

Cut rows (`mechkit.core.cuts`). Each reads three vectors of its cut's two joints, each a fixed
homogeneous 4-vector mapped by a joint placement: X = R_a t (or u), the direction fixed in frame_a;
Y = p_b (a position row) or R_b w (an alignment row); Z = p_a (a position row) or 0. Then

- residual  e = X . (Y - Z);
- row wrench W = [f X, Y x X] (f = 1 for a position row, 0 for an alignment row), world axes, moment
  about the world origin, so that de/dt = W . (V_b - V_a) with V_j = [v_O, omega] the world twist of
  joint j at the world origin: the Jacobian is (W @ J_world) * mask (Pinocchio's `data.J` after
  `computeJointJacobians`; mask +1 on the columns moving only frame_b, -1 on those moving only frame_a);
- drift gamma = W . (A_b - A_a) + dW/dt . (V_b - V_a), A_j the spatial acceleration of joint j at zero
  joint accelerations (world, origin), so that d2e/dt2 = J a + gamma;
- the wrench a cut transmits, frame_a's side on frame_b's side, from its rows' multipliers lambda
  (sign: J^T lambda is the generalised constraint force): sum of lambda W over its rows.

Coupling rows (`mechkit.core.records.Coupling`) read joint values (`mechkit.core.coupling_rows`). They
transmit no wrench through the tree (a coupling acts along its joints' freedoms, as a motor does).

Rows are ordered cut by cut, then the couplings. Arrays carry any leading sample axes; placements
G are (..., n_used, 4, 4) for `joints`, the joints carrying a cut frame.
"""

from __future__ import annotations

import itertools

import numpy as np
import pinocchio as pin

from mechkit.base.spatial import LEVI_CIVITA
from mechkit.core.coupling_rows import CouplingRow, coupling_drift, coupling_jacobian, coupling_residual
from mechkit.core.cuts import CutRows
from mechkit.core.tree_paths import subtree_incidence, support_columns

#: (12, 6) map of (Y' outer X).reshape(12), Y' = [Y, f], to the row wrench [f X, Y x X].
WRENCH_MAP = np.zeros((12, 6))
WRENCH_MAP[:9, 3:] = LEVI_CIVITA
WRENCH_MAP[9:, :3] = np.eye(3)
#: (24, 7) map of ([Z', Y'] outer X).reshape(24) to [W, e]: the wrench and the residual X . (Y - Z).
WRENCH_RESIDUAL_MAP = np.zeros((24, 7))
WRENCH_RESIDUAL_MAP[12:, :6] = WRENCH_MAP
WRENCH_RESIDUAL_MAP[[0, 4, 8], 6], WRENCH_RESIDUAL_MAP[[12, 16, 20], 6] = -1.0, 1.0


#: (9, 6) map of (p outer f).reshape(9) to [0, -p x f]: a wrench [f, m] about the origin moved to p.
MOMENT_SHIFT = np.zeros((9, 6))
MOMENT_SHIFT[:, 3:] = -LEVI_CIVITA
#: (6, 16) map of a twist [v_O, omega] to the transpose of Xi = [[omega x, v_O], [0, 0]], flattened: the
#: rate of a placement is dG/dt = Xi G.
TWIST_MATRIX_T = np.zeros((6, 16))
for _k, (_row, _col, _sign) in enumerate(((0, 3, 1), (1, 3, 1), (2, 3, 1))):
    TWIST_MATRIX_T[_k, 4 * _col + _row] = _sign
for _k, _entries in ((3, ((2, 1, 1), (1, 2, -1))), (4, ((0, 2, 1), (2, 0, -1))), (5, ((1, 0, 1), (0, 1, -1)))):
    for _row, _col, _sign in _entries:  # Xi[row, col] = sign omega_k
        TWIST_MATRIX_T[_k, 4 * _col + _row] = _sign


class ClosureKernel:
    """The rows of a set of cuts and couplings over one Pinocchio model, as numpy maps.

    Attributes:
        cuts, couplings: the rows' sources, in row order.
        joints: (n_used,) ids of the joints carrying frame_a or frame_b of some cut.
        cut_size: rows of the cuts; size: all rows (cuts, then couplings); ncuts: number of cuts.
        cut_slices: each cut's rows (a slice of the rows).
        mask: (cut_size, nv) Jacobian column signs (+1 frame_b only, -1 frame_a only, 0 both or none).
        support: (n_used, nv) 1 on the columns moving each used joint.
        incidence: (njoints, ncuts) `subtree_incidence`.
    """

    def __init__(self, model: pin.Model, cuts: list[CutRows], couplings: list[CouplingRow] = ()):
        frames = model.frames
        self.nv = model.nv
        self.cuts, self.couplings = tuple(cuts), tuple(couplings)
        self.joints = np.array(sorted({frames[f].parentJoint for c in cuts for f in (c.frame_a, c.frame_b)}), dtype=int)
        where = {int(j): k for k, j in enumerate(self.joints)}
        ia, ib, local, cut_of_row = [], [], [], []
        for c, cut in enumerate(cuts):
            Ma, Mb = frames[cut.frame_a].placement.homogeneous, frames[cut.frame_b].placement.homogeneous
            ja, jb = where[frames[cut.frame_a].parentJoint], where[frames[cut.frame_b].parentJoint]
            for t in cut.positions.T:
                ia.append(ja), ib.append(jb), cut_of_row.append(c)
                local.append([Ma[:, :3] @ t, Ma[:, 3], Mb[:, 3]])
            for u, w in cut.alignments:
                ia.append(ja), ib.append(jb), cut_of_row.append(c)
                local.append([Ma[:, :3] @ u, np.zeros(4), Mb[:, :3] @ w])
        self.cut_size = len(ia)
        self.size = self.cut_size + len(self.couplings)
        self.ncuts = len(cuts)
        self._ia, self._ib = np.array(ia, dtype=int), np.array(ib, dtype=int)
        row_sum = (np.array(cut_of_row, dtype=int)[None, :] == np.arange(self.ncuts)[:, None]).astype(float)
        bounds = np.cumsum([0] + [c.size for c in cuts])
        self.cut_slices = tuple(slice(int(a), int(b)) for a, b in itertools.pairwise(bounds))
        # every vector the rows read (X, Z, Y of each row, then p_b of each cut) as one map of the stacked placements
        vectors = [
            *np.array(local, dtype=float).reshape(-1, 4),
            *(frames[c.frame_b].placement.homogeneous[:, 3] for c in cuts),
        ]
        owners = [
            *np.stack([self._ia, self._ia, self._ib], axis=1).reshape(-1),
            *(where[frames[c.frame_b].parentJoint] for c in cuts),
        ]
        self._map = np.zeros((len(vectors), 4 * self.joints.size))
        for r, (j, vector) in enumerate(zip(owners, vectors)):
            self._map[r, 4 * j : 4 * j + 4] = vector
        self.support = np.array([support_columns(model, int(j)) for j in self.joints]).reshape(-1, model.nv)
        self.mask = self.support[self._ib] - self.support[self._ia]
        self.incidence = subtree_incidence(model, list(cuts))
        self._relative = np.zeros((self.cut_size, self.joints.size))  # twists of frame_b's joint minus frame_a's
        np.add.at(self._relative, (np.arange(self.cut_size), self._ib), 1.0)
        np.add.at(self._relative, (np.arange(self.cut_size), self._ia), -1.0)
        # row wrenches times multipliers -> what every joint transmits (tree joints minus their subtree's cuts,
        # then the cuts)
        self._transmission = np.concatenate([-(self.incidence[1:] @ row_sum), row_sum])

    # ------------------------------------------------------------ cut rows
    def world(self, G: np.ndarray) -> np.ndarray:
        """Every homogeneous world vector the rows read: one product of a fixed map with the placements
        transposed and stacked.

        Args:
            G: (..., n_used, 4, 4) world placements of the used joints (`joints`).

        Returns:
            (..., 3 cut_size + ncuts, 4) X', Z', Y' of each cut row (row by row), then p_b' of each cut.
        """
        return self.stacked_world(np.swapaxes(G, -1, -2).reshape(*G.shape[:-3], 4 * G.shape[-3], 4))

    def stacked_world(self, T: np.ndarray) -> np.ndarray:
        """`world` from the placements transposed and stacked.

        Args:
            T: (..., 4 n_used, 4) the used joints' world placements, T[4 j + c, a] = G_j[a, c].

        Returns:
            (..., 3 cut_size + ncuts, 4) the vectors of `world`.
        """
        return self._map @ T

    def _xzy(self, V: np.ndarray) -> np.ndarray:
        """(..., cut_size, 3, 4) X', Z', Y' of every cut row from `world` vectors."""
        return V[..., : 3 * self.cut_size, :].reshape(*V.shape[:-2], self.cut_size, 3, 4)

    def vectors(self, G: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The vectors X', Y', Z' every cut row reads, world (m or unit).

        Args:
            G: (..., n_used, 4, 4) world placements of the used joints.

        Returns:
            X', Y', Z', each (..., cut_size, 4), homogeneous.
        """
        xzy = self._xzy(self.world(G))
        return xzy[..., 0, :], xzy[..., 2, :], xzy[..., 1, :]

    def wrenches(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """The cut rows' wrenches [f X, Y x X].

        Args:
            x: (..., cut_size, 4) X' of every cut row (`vectors`).
            y: (..., cut_size, 4) Y' of every cut row (`vectors`).

        Returns:
            (..., cut_size, 6) row wrenches [force, moment about the world origin], world axes.
        """
        outer = y[..., :, None] * x[..., None, :3]
        return outer.reshape(*outer.shape[:-2], 12) @ WRENCH_MAP

    def row_wrenches(self, G: np.ndarray) -> np.ndarray:
        """The cut rows' wrenches from placements.

        Args:
            G: (..., n_used, 4, 4) world placements of the used joints.

        Returns:
            (..., cut_size, 6) row wrenches [force, moment about the world origin], world axes.
        """
        x, y, _ = self.vectors(G)
        return self.wrenches(x, y)

    def points(self, V: np.ndarray) -> np.ndarray:
        """The origins p_b of frame_b of every cut, from `world` vectors.

        Args:
            V: (..., 3 cut_size + ncuts, 4) vectors of `world`.

        Returns:
            (..., ncuts, 3) the points, world (m).
        """
        return V[..., 3 * self.cut_size :, :3]

    def cut_points(self, G: np.ndarray) -> np.ndarray:
        """The origins p_b of frame_b of every cut, from placements.

        Args:
            G: (..., n_used, 4, 4) world placements of the used joints.

        Returns:
            (..., ncuts, 3) the points, world (m).
        """
        return self.points(self.world(G))

    # ------------------------------------------------------------ all rows
    def residual(self, G: np.ndarray, q: np.ndarray) -> np.ndarray:
        """Every row's residual.

        Args:
            G: (..., n_used, 4, 4) world placements of the used joints.
            q: (..., nq) configurations (coupling rows).

        Returns:
            (..., size) residuals: m for position rows, dimensionless for alignment rows, rad or m for
            couplings.
        """
        x, y, z = self.vectors(G)
        cut = np.sum(x * (y - z), axis=-1)
        if not self.couplings:
            return cut
        return np.concatenate([cut, coupling_residual(self.couplings, q)], axis=-1)

    def evaluate(self, G: np.ndarray, J: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Residuals, Jacobian and cut row wrenches from placements (`rows` of `world`).

        Args:
            G: (..., n_used, 4, 4) world placements of the used joints.
            J: (..., 6, nv) joint Jacobians `data.J` (WORLD, after `computeJointJacobians`).
            q: (..., nq) configurations (coupling rows).

        Returns:
            Residuals (..., size), Jacobian (..., size, nv) and cut row wrenches (..., cut_size, 6).
        """
        return self.rows(self.world(G), J, q)

    def rows(self, V: np.ndarray, J: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Residuals, Jacobian and cut row wrenches from `world` vectors, in one product.

        Args:
            V: (..., 3 cut_size + ncuts, 4) vectors of `world`.
            J: (..., 6, nv) joint Jacobians `data.J` (WORLD, after `computeJointJacobians`).
            q: (..., nq) configurations (coupling rows).

        Returns:
            Residuals (..., size), Jacobian (..., size, nv) and cut row wrenches (..., cut_size, 6).
        """
        xzy = self._xzy(V)
        outer = xzy[..., 1:, :, None] * xzy[..., 0, None, None, :3]
        we = outer.reshape(*V.shape[:-2], self.cut_size, 24) @ WRENCH_RESIDUAL_MAP
        W, e = we[..., :6], we[..., 6]
        jac = (W @ J) * self.mask
        if self.couplings:
            e = np.concatenate([e, coupling_residual(self.couplings, q)], axis=-1)
            jac = np.concatenate([jac, coupling_jacobian(self.couplings, q, self.nv)], axis=-2)
        return e, jac, W

    def jacobian(self, W: np.ndarray, J: np.ndarray, q: np.ndarray) -> np.ndarray:
        """The closure Jacobian from the cut row wrenches.

        Args:
            W: (..., cut_size, 6) cut row wrenches.
            J: (..., 6, nv) joint Jacobians `data.J` (WORLD).
            q: (..., nq) configurations (coupling rows).

        Returns:
            (..., size, nv) the closure Jacobian.
        """
        jac = (W @ J) * self.mask
        if not self.couplings:
            return jac
        return np.concatenate([jac, coupling_jacobian(self.couplings, q, self.nv)], axis=-2)

    def twists(self, J: np.ndarray, v: np.ndarray) -> np.ndarray:
        """World twists of the used joints (also: with `data.dJ`, their accelerations at a = 0).

        Args:
            J: (..., 6, nv) joint Jacobians `data.J` (or their rates `data.dJ`), WORLD.
            v: (..., nv) velocities.

        Returns:
            (..., n_used, 6) [v_O, omega] of each used joint, world axes, at the world origin.
        """
        return np.swapaxes(J @ np.swapaxes(self.support * v[..., None, :], -1, -2), -1, -2)

    def drift(
        self,
        G: np.ndarray,
        V: np.ndarray,
        A: np.ndarray,
        q: np.ndarray,
        v: np.ndarray,
        world: np.ndarray | None = None,
        W: np.ndarray | None = None,
    ) -> np.ndarray:
        """(..., size) gamma with d2e/dt2 = J a + gamma.

        A vector fixed in joint j's frame moves as its placement, dG/dt = Xi G with Xi = [[omega x, v_O],
        [0, 0]] of the joint's twist: the vectors' rates are `world` of the rates of the placements, and
        gamma = W . (A_b - A_a) + dW/dt . (V_b - V_a) (see the module docstring).

        Args:
            G: (..., n_used, 4, 4) world placements of the used joints.
            V: (..., n_used, 6) their world twists (`twists`).
            A: (..., n_used, 6) their world accelerations at a = 0 (`twists` of `data.dJ`).
            q: (..., nq) configurations (coupling rows).
            v: (..., nv) velocities (coupling rows).
            world: `world(G)` where the caller has it (`rows`), else None.
            W: (..., cut_size, 6) the row wrenches where the caller has them (`rows`), else None.

        Returns:
            (..., size) the drift gamma.
        """
        world = self.world(G) if world is None else world
        xzy = self._xzy(world)
        x, y = xzy[..., 0, :], xzy[..., 2, :]
        W = self.wrenches(x, y) if W is None else W
        lead, n = G.shape[:-3], G.shape[-3]
        rates = (np.swapaxes(G, -1, -2) @ (V @ TWIST_MATRIX_T).reshape(*lead, n, 4, 4)).reshape(*lead, 4 * n, 4)
        dot = self._xzy(self._map @ rates)
        outer = y[..., :, None] * dot[..., 0, None, :3] + dot[..., 2, :, None] * x[..., None, :3]
        Wdot = outer.reshape(*lead, self.cut_size, 12) @ WRENCH_MAP
        cut = np.sum(W * (self._relative @ A) + Wdot * (self._relative @ V), axis=-1)
        if not self.couplings:
            return cut
        return np.concatenate([cut, coupling_drift(self.couplings, q, v)], axis=-1)

    # ------------------------------------------------------------ what multipliers transmit
    def joint_loads(self, W: np.ndarray, lam: np.ndarray, origins: np.ndarray, cut_points: np.ndarray) -> np.ndarray:
        """What the multipliers transmit through every joint: (..., njoints - 1 + ncuts, 6).

        Tree joints (model order, the universe left out): minus the share of the cut wrenches acting on
        their subtree; then the cuts: their wrenches. Each [f, m about the joint's point], world.

        Args:
            W: (..., cut_size, 6) row wrenches.
            lam: (..., size) row multipliers.
            origins: (..., njoints - 1, 3) tree joint origins, world (m).
            cut_points: (..., ncuts, 3) the cuts' points p_b, world (m).

        Returns:
            (..., njoints - 1 + ncuts, 6) [f, m about the joint's point], world axes.
        """
        loads = (self._transmission * lam[..., None, : self.cut_size]) @ W  # about the world origin
        points = np.concatenate([origins, cut_points], axis=-2)
        outer = points[..., :, :, None] * loads[..., :, None, :3]
        loads += outer.reshape(*outer.shape[:-2], 9) @ MOMENT_SHIFT
        return loads

    def load_map(self, W: np.ndarray, origins: np.ndarray, cut_points: np.ndarray) -> np.ndarray:
        """`joint_loads` as a matrix: joint_loads(W, lam, ...) = load_map(W, ...) @ lam[:cut_size].

        Args:
            W: (..., cut_size, 6) row wrenches.
            origins: (..., njoints - 1, 3) tree joint origins, world (m).
            cut_points: (..., ncuts, 3) the cuts' points p_b, world (m).

        Returns:
            (..., njoints - 1 + ncuts, 6, cut_size) what each cut row's unit multiplier transmits through
            every joint, [f, m about the joint's point], world axes.
        """
        L = self._transmission[:, None, :] * np.swapaxes(W, -1, -2)[..., None, :, :]  # about the world origin
        p = np.concatenate([origins, cut_points], axis=-2)[..., None]
        f = L[..., :3, :]
        for k, (a, b) in enumerate(((1, 2), (2, 0), (0, 1))):  # m about p = m about the origin - p x f
            L[..., 3 + k, :] -= p[..., a, :] * f[..., b, :] - p[..., b, :] * f[..., a, :]
        return L
