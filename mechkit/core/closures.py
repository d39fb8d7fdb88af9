"""Loop-closure rows: residual, Jacobian and acceleration drift of every cut, and Pinocchio's view of them.

Every row is one of two exact forms, so that its Jacobian is its exact derivative everywhere:

- a position row   e = t . (p_b - p_a), t = R_a t_local a unit vector fixed in frame_a;
- an alignment row e = u . w, u = R_a u_local fixed in frame_a, w = R_b w_local fixed in frame_b
  (u and w perpendicular when the cut is closed).

The wrench a closure transmits, parent (frame_a side) on child (frame_b side), is
f = sum_t lambda_t t at p_b and m = sum_(u,w) lambda (w x u): `ClosureRows.wrenches` returns it.

`RowEvaluator` evaluates the rows in numpy from one gather of joint placements, for one sample or
many, without per-frame Pinocchio calls. Every row reads three vectors of its cut's two joints, each
a fixed homogeneous 4-vector mapped by a joint placement: X = R_a t (or u), the direction fixed in
frame_a; Y = p_b (a position row) or R_b w (an alignment row); Z = p_a (a position row) or 0. Then

- residual  e = X . (Y - Z);
- row wrench W = [f X, Y x X] (f = 1 for a position row, 0 for an alignment row), world axes, moment
  about the world origin, so that de/dt = W . (V_b - V_a) with V_j = [v_O, omega] the world twist of
  joint j at the world origin: the Jacobian is (W @ J_world) * mask (Pinocchio's `data.J` after
  `computeJointJacobians`; mask +1 on the columns moving only frame_b, -1 on those moving only frame_a);
- drift gamma = W . (A_b - A_a) + dW/dt . (V_b - V_a), A_j the spatial acceleration of joint j at zero
  joint accelerations (world, origin), so that d2e/dt2 = J a + gamma.

Its arrays carry any leading sample axes; placements G are (..., n_used, 4, 4) for its `joints`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription, MethodUnavailable
from mechkit.base.spatial import LEVI_CIVITA, cross, cross_batch
from mechkit.core.records import LoopClosure

#: Offset (m) along a revolute axis of the second point anchor that Pinocchio's 3D constraints use.
AXIS_ANCHOR_OFFSET = 0.1


def _perpendicular_pair(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit t1, t2 with (t1, t2, n) right-handed."""
    helper = np.array([1.0, 0, 0]) if abs(n[0]) < 0.9 else np.array([0, 1.0, 0])
    t1 = cross(n, helper)
    t1 /= np.linalg.norm(t1)
    return t1, cross(n, t1)


@dataclass(frozen=True)
class CutRows:
    """The rows of one closure, in its frames' coordinates.

    Attributes:
        closure: the declaration.
        frame_a, frame_b: Pinocchio frame ids.
        positions: (3, k) position-row directions t in frame_a.
        alignments: list of (u in frame_a, w in frame_b) alignment rows.
    """

    closure: LoopClosure
    frame_a: int
    frame_b: int
    positions: np.ndarray
    alignments: tuple[tuple[np.ndarray, np.ndarray], ...]

    @property
    def size(self) -> int:
        """Number of rows the cut keeps (position rows + alignment rows)."""
        return self.positions.shape[1] + len(self.alignments)


def cut_rows(model: pin.Model, closure: LoopClosure, rows: str | None = None) -> CutRows:
    """The rows a closure keeps (its own `rows` set unless `rows` overrides it)."""
    rows = rows or closure.rows
    ids = []
    for frame in (closure.frame_a, closure.frame_b):
        if not model.existFrame(frame):
            raise MalformedDescription(f"mechkit:loop {closure.name!r}", f"frame {frame!r} not in the model")
        ids.append(model.getFrameId(frame))
    eye = np.eye(3)
    kind = closure.kind
    positions: list[np.ndarray] = []
    alignments: list[tuple[np.ndarray, np.ndarray]] = []
    n = closure.axis
    if n is not None:
        t1, t2 = _perpendicular_pair(n)
    frame_fixed = [(eye[1], eye[2]), (eye[2], eye[0]), (eye[0], eye[1])]  # relative rotation locked
    if kind == "revolute":
        if rows in ("spatial", "planar"):
            positions = list(eye) if rows == "spatial" else [t1, t2]
        if rows in ("spatial", "spherical"):
            alignments = [(t1, n), (t2, n)]
    elif kind == "spherical":
        positions = list(eye) if rows == "spatial" else [t1, t2]
    elif kind == "hooke":
        if rows == "spatial":
            positions = list(eye)
        alignments = [(closure.axis_a, closure.axis_b)]
    elif kind == "weld":
        if rows == "spatial":
            positions, alignments = list(eye), frame_fixed
        elif rows == "planar":
            positions, alignments = [t1, t2], [(t1, t2)]
        else:
            alignments = frame_fixed
    elif kind == "prismatic":
        if rows != "spatial":
            raise MalformedDescription(f"mechkit:loop {closure.name!r}", "a prismatic cut supports rows='spatial' only")
        positions, alignments = [t1, t2], frame_fixed
    pos = np.array(positions).T if positions else np.zeros((3, 0))
    return CutRows(closure, ids[0], ids[1], pos, tuple(alignments))


def support_columns(model: pin.Model, joint: int) -> np.ndarray:
    """(nv,) 1.0 on the velocity columns of the joints from the root to `joint` (0: none)."""
    out = np.zeros(model.nv)
    while joint > 0:
        jm = model.joints[joint]
        out[jm.idx_v:jm.idx_v + jm.nv] = 1.0
        joint = model.parents[joint]
    return out


#: (12, 6) map of (Y' outer X).reshape(12), Y' = [Y, f], to the row wrench [f X, Y x X].
WRENCH_MAP = np.zeros((12, 6))
WRENCH_MAP[:9, 3:] = LEVI_CIVITA
WRENCH_MAP[9:, :3] = np.eye(3)
#: (24, 7) map of ([Z', Y'] outer X).reshape(24) to [W, e]: the wrench and the residual X . (Y - Z).
WRENCH_RESIDUAL_MAP = np.zeros((24, 7))
WRENCH_RESIDUAL_MAP[12:, :6] = WRENCH_MAP
WRENCH_RESIDUAL_MAP[[0, 4, 8], 6], WRENCH_RESIDUAL_MAP[[12, 16, 20], 6] = -1.0, 1.0


class RowEvaluator:
    """The rows of a list of cuts as numpy maps of the placements of the joints they involve.

    Each row's X, Z, Y are homogeneous 4-vectors (X' = [X, 0], Z' = [Z, f], Y' = [Y, f]): one product of
    the fixed local vectors with every used placement, one gather.

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
        ia, ib, local = [], [], []
        for cut in cuts:
            Ma, Mb = frames[cut.frame_a].placement.homogeneous, frames[cut.frame_b].placement.homogeneous
            ja, jb = where[frames[cut.frame_a].parentJoint], where[frames[cut.frame_b].parentJoint]
            for t in cut.positions.T:
                ia.append(ja), ib.append(jb), local.append([Ma[:, :3] @ t, Ma[:, 3], Mb[:, 3]])
            for u, w in cut.alignments:
                ia.append(ja), ib.append(jb), local.append([Ma[:, :3] @ u, np.zeros(4), Mb[:, :3] @ w])
        self.size = len(ia)
        self._ia, self._ib = np.array(ia, dtype=int), np.array(ib, dtype=int)
        self._local = np.array(local, dtype=float).reshape(-1, 4)  # (3 rows, 4): X, Z, Y of each row
        self._joint = np.stack([self._ia, self._ia, self._ib], axis=1).reshape(-1)
        self._slot = np.arange(3 * self.size)
        self._joint_list = self.joints.tolist()
        self.support = np.array([support_columns(model, int(j)) for j in self.joints]).reshape(-1, model.nv)
        self.mask = self.support[self._ib] - self.support[self._ia]

    def gather(self, data: pin.Data) -> np.ndarray:
        """(n_used, 4, 4) placements of the used joints from `data.oMi` (current after any forward pass)."""
        oMi = data.oMi.tolist()
        return np.array([oMi[j].np for j in self._joint_list]).reshape(-1, 4, 4)

    def _xzy(self, G: np.ndarray) -> np.ndarray:
        every = self._local @ np.swapaxes(G, -1, -2)  # (..., n_used, 3 rows, 4): each vector by each placement
        return every[..., self._joint, self._slot, :].reshape(*G.shape[:-3], self.size, 3, 4)

    def vectors(self, G: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """X', Y', Z' (..., rows, 4) of every row (world; m or unit) from placements (..., n_used, 4, 4)."""
        xzy = self._xzy(G)
        return xzy[..., 0, :], xzy[..., 2, :], xzy[..., 1, :]

    def residual(self, G: np.ndarray) -> np.ndarray:
        """(..., rows) residuals (m for position rows, dimensionless for alignment rows)."""
        x, y, z = self.vectors(G)
        return np.sum(x * (y - z), axis=-1)

    def wrenches(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """(..., rows, 6) row wrenches [force, moment about the world origin] from X', Y' (..., rows, 4)."""
        outer = y[..., :, None] * x[..., None, :3]
        return outer.reshape(*outer.shape[:-2], 12) @ WRENCH_MAP

    def evaluate(self, G: np.ndarray, J: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Residuals (..., rows) and Jacobian (..., rows, nv) from placements and `data.J` (..., 6, nv):
        one product of [Z', Y'] outer X with `WRENCH_RESIDUAL_MAP` (residual as X . Y - X . Z)."""
        xzy = self._xzy(G)
        outer = xzy[..., 1:, :, None] * xzy[..., 0, None, None, :3]
        we = outer.reshape(*outer.shape[:-3], 24) @ WRENCH_RESIDUAL_MAP
        return we[..., 6], (we[..., :6] @ J) * self.mask

    def twists(self, J: np.ndarray, v: np.ndarray) -> np.ndarray:
        """(..., n_used, 6) world twists [v_O, omega] of the used joints from world Jacobian columns
        (..., 6, nv) times velocities (..., nv) (also: with `data.dJ`, the accelerations at a = 0)."""
        return np.swapaxes(J @ np.swapaxes(self.support * v[..., None, :], -1, -2), -1, -2)

    def world_twists(self, G: np.ndarray, local: np.ndarray) -> np.ndarray:
        """(..., n_used, 6) local joint motions [linear, angular] (..., n_used, 6) (Pinocchio's `data.v`,
        `data.a`) in world axes about the world origin."""
        R, p = G[..., :3, :3], G[..., :3, 3]
        angular = (R @ local[..., 3:, None])[..., 0]
        return np.concatenate([(R @ local[..., :3, None])[..., 0] + cross_batch(p, angular), angular], axis=-1)

    def drift(self, G: np.ndarray, V: np.ndarray, A: np.ndarray) -> np.ndarray:
        """(..., rows) gamma with d2e/dt2 = J a + gamma, from the used joints' world twists V and
        accelerations at a = 0, A (..., n_used, 6): W . (A_b - A_a) + dW/dt . (V_b - V_a), with
        dX/dt = omega_a x X and dY/dt = f v_Ob + omega_b x Y."""
        x, y, _ = self.vectors(G)
        Va, Vb = V[..., self._ia, :], V[..., self._ib, :]
        xdot = cross_batch(Va[..., 3:], x[..., :3])
        ydot = y[..., 3:] * Vb[..., :3] + cross_batch(Vb[..., 3:], y[..., :3])
        outer = ydot[..., :, None] * x[..., None, :3]
        outer = np.concatenate([outer, np.zeros_like(outer[..., :1, :])], axis=-2) + y[..., :, None] * xdot[..., None, :]
        Wdot = outer.reshape(*outer.shape[:-2], 12) @ WRENCH_MAP
        Arel = A[..., self._ib, :] - A[..., self._ia, :]
        return np.sum(self.wrenches(x, y) * Arel + Wdot * (Vb - Va), axis=-1)


class ClosureRows:
    """All closures of a mechanism as one stacked set of rows, evaluated by `RowEvaluator`
    from one gather of the joint placements `data.oMi`.

    `residual` needs the joint placements current (any forward pass), `jacobian` also the joint
    Jacobians (`pin.computeJointJacobians`), `drift` the joint velocities and accelerations
    (`pin.forwardKinematics(model, data, q, v, 0 * v)`).
    """

    def __init__(self, model: pin.Model, cuts: list[CutRows]):
        self.model = model
        self.cuts = cuts
        self.size = sum(c.size for c in cuts)
        self.evaluator = RowEvaluator(model, cuts)

    def residual(self, data: pin.Data) -> np.ndarray:
        """Row residuals (m for position rows, dimensionless for alignment rows); joint placements must be current."""
        return self.evaluator.residual(self.evaluator.gather(data))

    def evaluate(self, data: pin.Data) -> tuple[np.ndarray, np.ndarray]:
        """Residuals (rows,) and Jacobian (rows, nv) from one gather; needs `pin.computeJointJacobians`."""
        return self.evaluator.evaluate(self.evaluator.gather(data), data.J.reshape(6, self.model.nv))

    def jacobian(self, data: pin.Data) -> np.ndarray:
        """d(residual)/dq as (rows, nv); needs `pin.computeJointJacobians`."""
        return self.evaluate(data)[1]

    def drift(self, data: pin.Data) -> np.ndarray:
        """gamma such that d2(residual)/dt2 = J a + gamma.

        Needs `pin.forwardKinematics(model, data, q, v, 0 * v)`.
        """
        ev = self.evaluator
        G = ev.gather(data)
        v, a = data.v.tolist(), data.a.tolist()
        local = np.array([[v[j].np, a[j].np] for j in ev.joints]).reshape(-1, 2, 6)
        return ev.drift(G, ev.world_twists(G, local[:, 0]), ev.world_twists(G, local[:, 1]))

    def gather(self, data: pin.Data, q: np.ndarray,
               v: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """One Pinocchio pass per sample of q (N, nq) (and v (N, nv)): the used joint placements
        (N, n_used, 4, 4), world joint Jacobians `data.J` (N, 6, nv) and, with v, their time derivatives
        `data.dJ` (N, 6, nv). Leaves data at the last sample, frame placements updated."""
        model, ev = self.model, self.evaluator
        n, nv = len(q), model.nv
        G = np.empty((n, len(ev.joints), 4, 4))
        J = np.empty((n, 6, nv))
        dJ = None if v is None else np.empty((n, 6, nv))
        for i in range(n):
            if v is None:
                pin.computeJointJacobians(model, data, q[i])
            else:
                pin.computeJointJacobiansTimeVariation(model, data, q[i], v[i])
                dJ[i] = data.dJ.reshape(6, nv)
            G[i] = ev.gather(data)
            J[i] = data.J.reshape(6, nv)
        pin.updateFramePlacements(model, data)
        return G, J, dJ

    def jacobian_derivatives(self, data: pin.Data, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """(N, 6, nv) time derivatives of the world joint Jacobians `data.dJ` at N samples (q, v)."""
        model = self.model
        out = np.empty((len(q), 6, model.nv))
        for i in range(len(q)):
            pin.computeJointJacobiansTimeVariation(model, data, q[i], v[i])
            out[i] = data.dJ.reshape(6, model.nv)
        return out

    def wrenches(self, data: pin.Data, lam: np.ndarray) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """Per cut, (force, moment, point): the wrench frame_a's side exerts on frame_b's side.

        World frame, N and N m, moment about `point` = p_b (m). `lam` are the row multipliers in the
        sign convention J^T lam = generalised constraint force.
        """
        out = []
        i = 0
        for cut in self.cuts:
            oMa, oMb = data.oMf[cut.frame_a], data.oMf[cut.frame_b]
            k = cut.positions.shape[1]
            force = oMa.rotation @ cut.positions @ lam[i:i + k]
            i += k
            moment = np.zeros(3)
            for u, w in cut.alignments:
                moment += cross(oMb.rotation @ w, oMa.rotation @ u) * lam[i]
                i += 1
            out.append((force, moment, oMb.translation.copy()))
        return out


def rigid_constraint_models(model: pin.Model, cuts: list[CutRows]) -> list[pin.RigidConstraintModel]:
    """Pinocchio's legacy constraint models equivalent to the cuts (for `pin.constraintDynamics`).

    Weld -> one 6D anchor; spherical and planar revolute -> one 3D point anchor; spatial or
    spherical-rows revolute -> two 3D point anchors on the axis. Redundant rows are left to the
    proximal regularisation. Hooke and prismatic cuts have no equivalent: `MethodUnavailable`.
    """
    out = []
    for cut in cuts:
        c = cut.closure
        fa, fb = model.frames[cut.frame_a], model.frames[cut.frame_b]
        if c.kind == "weld":
            out.append(pin.RigidConstraintModel(pin.ContactType.CONTACT_6D, model, fa.parentJoint, fa.placement,
                                                fb.parentJoint, fb.placement, pin.ReferenceFrame.LOCAL))
            continue
        if c.kind in ("hooke", "prismatic"):
            raise MethodUnavailable("pin.constraintDynamics",
                                    f"cut {c.name!r} is {c.kind}: no RigidConstraintModel expresses it; use method='kkt'")
        offsets = [np.zeros(3)]
        if c.kind == "revolute" and (c.rows != "planar"):
            offsets.append(AXIS_ANCHOR_OFFSET * c.axis)
        for offset in offsets:
            pa = fa.placement * pin.SE3(np.eye(3), offset)
            pb = fb.placement * pin.SE3(np.eye(3), offset)
            out.append(pin.RigidConstraintModel(pin.ContactType.CONTACT_3D, model, fa.parentJoint, pa,
                                                fb.parentJoint, pb, pin.ReferenceFrame.LOCAL))
    return out
