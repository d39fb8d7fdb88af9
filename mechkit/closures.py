"""Loop-closure rows: residual, Jacobian and acceleration drift of every cut, and Pinocchio's view of them.

Every row is one of two exact forms, so that its Jacobian is its exact derivative everywhere:

- a position row   e = t . (p_b - p_a), t = R_a t_local a unit vector fixed in frame_a;
- an alignment row e = u . w, u = R_a u_local fixed in frame_a, w = R_b w_local fixed in frame_b
  (u and w perpendicular when the cut is closed).

Velocities and accelerations use Pinocchio frame Jacobians in LOCAL_WORLD_ALIGNED (world axes,
frame origin). The wrench a closure transmits, parent (frame_a side) on child (frame_b side), is
f = sum_t lambda_t t at p_b and m = sum_(u,w) lambda (w x u): `ClosureRows.wrenches` returns it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit.description import LoopClosure
from mechkit.exceptions import MalformedDescription, MethodUnavailable
from mechkit.spatial import cross, skew

LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
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
    """All closures of a mechanism as one stacked set of rows.

    Call `update(data)` after `pin.framesForwardKinematics` / `computeJointJacobians` so that the
    frame placements are current; then `residual`, `jacobian`, `drift` read them.
    """

    def __init__(self, model: pin.Model, cuts: list[CutRows]):
        self.model = model
        self.cuts = cuts
        self.size = sum(c.size for c in cuts)

    def residual(self, data: pin.Data) -> np.ndarray:
        """Row residuals (m for position rows, dimensionless for alignment rows); frames must be current."""
        out = np.empty(self.size)
        i = 0
        for cut in self.cuts:
            oMa, oMb = data.oMf[cut.frame_a], data.oMf[cut.frame_b]
            d = oMb.translation - oMa.translation
            k = cut.positions.shape[1]
            out[i:i + k] = (oMa.rotation @ cut.positions).T @ d
            i += k
            for u, w in cut.alignments:
                out[i] = (oMa.rotation @ u) @ (oMb.rotation @ w)
                i += 1
        return out

    def jacobian(self, data: pin.Data) -> np.ndarray:
        """d(residual)/dq as (rows, nv); needs `pin.computeJointJacobians` and frame placements."""
        out = np.empty((self.size, self.model.nv))
        i = 0
        for cut in self.cuts:
            Ja = pin.getFrameJacobian(self.model, data, cut.frame_a, LWA).reshape(6, -1)  # (6,) when nv = 1
            Jb = pin.getFrameJacobian(self.model, data, cut.frame_b, LWA).reshape(6, -1)
            oMa, oMb = data.oMf[cut.frame_a], data.oMf[cut.frame_b]
            d = oMb.translation - oMa.translation
            T = oMa.rotation @ cut.positions
            k = T.shape[1]
            if k:
                out[i:i + k] = T.T @ (Jb[:3] - Ja[:3] + skew(d) @ Ja[3:])
            i += k
            for u, w in cut.alignments:
                uw, ww = oMa.rotation @ u, oMb.rotation @ w
                out[i] = cross(ww, uw) @ (Jb[3:] - Ja[3:])
                i += 1
        return out

    def drift(self, data: pin.Data) -> np.ndarray:
        """gamma such that d2(residual)/dt2 = J a + gamma.

        Needs `pin.forwardKinematics(model, data, q, v, 0 * v)` and `updateFramePlacements`.
        """
        out = np.empty(self.size)
        i = 0
        model = self.model
        for cut in self.cuts:
            va = pin.getFrameVelocity(model, data, cut.frame_a, LWA)
            vb = pin.getFrameVelocity(model, data, cut.frame_b, LWA)
            aa = pin.getFrameClassicalAcceleration(model, data, cut.frame_a, LWA)
            ab = pin.getFrameClassicalAcceleration(model, data, cut.frame_b, LWA)
            oMa, oMb = data.oMf[cut.frame_a], data.oMf[cut.frame_b]
            d = oMb.translation - oMa.translation
            dv = vb.linear - va.linear
            wa, wb = va.angular, vb.angular
            k = cut.positions.shape[1]
            if k:
                # d2/dt2 of t.d with t fixed in frame_a: t.(da + d x alpha_a + dv x w_a + (dv + d x w_a) x w_a)
                g = (ab.linear - aa.linear + cross(d, aa.angular) + cross(dv, wa) + cross(dv + cross(d, wa), wa))
                out[i:i + k] = (oMa.rotation @ cut.positions).T @ g
                i += k
            for u_local, w_local in cut.alignments:
                u, w = oMa.rotation @ u_local, oMb.rotation @ w_local
                n = cross(w, u)
                ndot = cross(cross(wb, w), u) + cross(w, cross(wa, u))
                out[i] = n @ (ab.angular - aa.angular) + ndot @ (wb - wa)
                i += 1
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
