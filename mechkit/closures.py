"""Loop-closure rows: residual, Jacobian and acceleration drift of every cut, and Pinocchio's view of them.

Every row is one of two exact forms, so that its Jacobian is its exact derivative everywhere:

- a position row   e = t . (p_b - p_a), t = R_a t_local a unit vector fixed in frame_a;
- an alignment row e = u . w, u = R_a u_local fixed in frame_a, w = R_b w_local fixed in frame_b
  (u and w perpendicular when the cut is closed).

They are evaluated in numpy from the joint placements, world joint Jacobians and joint motions
(`mechkit.closure_eval`), without per-frame Pinocchio calls. The wrench a closure transmits, parent (frame_a side) on child (frame_b side), is
f = sum_t lambda_t t at p_b and m = sum_(u,w) lambda (w x u): `ClosureRows.wrenches` returns it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit.closure_eval import RowEvaluator
from mechkit.description import LoopClosure
from mechkit.exceptions import MalformedDescription, MethodUnavailable
from mechkit.spatial import cross

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


class ClosureRows:
    """All closures of a mechanism as one stacked set of rows, evaluated by `closure_eval.RowEvaluator`
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
