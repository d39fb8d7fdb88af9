"""Independent computations on closed-loop robots, with Pinocchio calls only (no mechkit core, no mechkit reader;
mechkit's `Coupling` record only carries numbers).

What lives here:

- `gepetto_load`: an Extended-URDF pair read the way Gepetto's loader reads it (example-parallel-robots'
  `loader_tools.completeRobotLoader` then `simplifyModel`, toolbox-parallel-robots' `freezeJoints`),
  re-written from their semantics: joint substitutions by name, spherical triplets found by consecutive
  joint ids, constraints re-attached through frames named after their joints. A reader that builds a
  different model shows up as a disagreement with it.
- `urdf_plus_load`, `urdf_mimics`: URDF+ loops and couplings and URDF mimic joints read with an XML parser.
- `study`: on any model, its cuts and its coupling rows, the closure by damped least squares on the
  frame errors (3d: position error in the world frame, 6d: log6 of the relative placement), the
  numerical DOF from the rank of the constraint Jacobian at the closed configuration, and the motor
  torques holding gravity at rest from `[S, J^T] [tau; lambda] = g` (g = rnea(q, 0, 0)), least squares,
  with whether g lies in the range (whether the motors can hold) and which torques it fixes. Loops that
  do not close are refused by `require_closed`, naming the robot, the worst cut and the residual.
- `idle`: the idle freedoms at a closed configuration, body by body (welded bodies one body).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pinocchio as pin
import yaml

from mechkit.core.records import (
    Coupling,  # a plain record (name, follower, leader, polynomial): no computation
)

#: Rank judgement: singular values below this fraction of the largest one are zero.
RANK_TOL = 1e-9
#: Closure tolerance of the damped least squares (m for 3d rows, m and rad for 6d rows).
CLOSURE_TOL = 1e-12


@dataclass(frozen=True)
class Cut:
    """A loop closure as Pinocchio sees it: frame a on joint_a at place_a, frame b likewise.

    rows: "3d" (origins coincide), "6d" (frames coincide) or "revolute" (origins coincide, the rotation
    about `axis`, given in frame a, free).
    """

    name: str
    joint_a: int
    place_a: pin.SE3
    joint_b: int
    place_b: pin.SE3
    rows: str
    axis: np.ndarray | None = None


class LoopsDoNotClose(Exception):
    """The damped least squares could not close a robot's loops: the worst cut and its error (m, rad)."""

    def __init__(self, robot: str, cut: str, residual: float):
        self.robot, self.cut, self.residual = robot, cut, residual
        super().__init__(
            f"{robot}: the loops do not close: cut {cut!r} keeps an error of {residual:.2e} (m, rad) "
            "at the damped least-squares minimum"
        )


@dataclass
class Study:
    """What `study` found. Torques in N m (N for prismatic motors), residuals in m and rad."""

    q: np.ndarray
    closed: bool
    residual: float
    dof: int
    rank: int
    undriven: int
    holds: bool
    gravity_residual: float
    torques: dict[str, float] = field(default_factory=dict)
    torques_unique: bool = True
    determined: tuple[str, ...] = ()


def _frame_cut(model: pin.Model, name: str, frame_a: str, frame_b: str, rows: str, axis=None) -> Cut:
    fa, fb = (model.frames[model.getFrameId(n)] for n in (frame_a, frame_b))
    return Cut(name, fa.parentJoint, fa.placement, fb.parentJoint, fb.placement, rows, axis)


def cuts_of(model: pin.Model, closures) -> list[Cut]:
    """Cuts from closure records (objects with name, kind, frame_a, frame_b, axis): spherical -> 3d,
    weld -> 6d, revolute -> revolute."""
    rows = {"spherical": "3d", "weld": "6d", "revolute": "revolute"}
    return [_frame_cut(model, c.name, c.frame_a, c.frame_b, rows[c.kind], c.axis) for c in closures]


# --- Gepetto's loader, re-read -------------------------------------------------------------------------

_AXES = {"X": pin.JointModelRX, "Y": pin.JointModelRY, "Z": pin.JointModelRZ}


def gepetto_load(urdf: Path, sidecar: Path, freeflyer: bool = False) -> tuple[pin.Model, list[Cut], list[str]]:
    """(model, cuts, motors) as Gepetto's `completeRobotLoader(path, urdf, yaml, freeflyer)` builds them.

    Raises:
        KeyError / IndexError: where Gepetto's loader fails too (a frame or a joint it cannot find).
    """
    tree = (
        pin.buildModelFromUrdf(str(urdf), pin.JointModelFreeFlyer()) if freeflyer else pin.buildModelFromUrdf(str(urdf))
    )
    content = yaml.safe_load(Path(sidecar).read_text())
    names = list(content.get("joint_name") or [])
    types = list(content.get("joint_type") or []) if names else []
    model, fixed = pin.Model(), []
    for jid in range(1, tree.njoints):
        place, name, joint = tree.jointPlacements[jid], tree.names[jid], tree.joints[jid]
        parent = model.getJointId(tree.names[tree.parents[jid]])
        kind = types[names.index(name)] if name in names else None
        if kind == "SPHERICAL":
            joint = pin.JointModelSpherical()
        elif kind == "FIXED":
            fixed.append(jid)  # Gepetto records the joint's id in the URDF model, not in the new one
        elif kind is not None and kind.startswith("UJOINT"):
            parent = model.addJoint(parent, _AXES[kind[-2]](), place, f"{name}_{kind[-2]}")
            joint, place, name = _AXES[kind[-1]](), pin.SE3.Identity(), f"{name}_{kind[-1]}"
        elif kind is not None:
            raise KeyError(f"joint_type {kind!r}")
        jid_new = model.addJoint(parent, joint, place, name)
        model.appendBodyToJoint(jid_new, tree.inertias[jid], pin.SE3.Identity())
    for frame in list(tree.frames)[1:]:  # the universe frame is the new model's own
        owner = tree.names[frame.parentJoint]
        kind = types[names.index(frame.name)] if frame.name in names else None
        if kind is not None and kind.startswith("UJOINT"):
            for axis in (kind[-2], kind[-1]):
                sub = f"{frame.name}_{axis}"
                model.addFrame(pin.Frame(sub, model.getJointId(sub), pin.SE3.Identity(), pin.FrameType.JOINT), False)
            continue
        owner_kind = types[names.index(owner)] if owner in names else None
        if owner_kind is not None and owner_kind.startswith("UJOINT"):
            owner = f"{owner}_{owner_kind[-1]}"
        model.addFrame(pin.Frame(frame.name, model.getJointId(owner), frame.placement, frame.type), False)
    model = pin.buildReducedModel(model, fixed, pin.neutral(model))
    cuts = []
    for (a, b), kind in zip(content["closed_loop"], content["type"]):
        cuts.append(_frame_cut(model, f"{a}C{b}", a, b, "3d" if kind in ("3D", "3d") else "6d"))
    model, cuts = _simplify(model, cuts)
    motors = [n for n in model.names if n in content["name_mot"]]
    return model, cuts, motors


def _simplify(model: pin.Model, cuts: list[Cut]) -> tuple[pin.Model, list[Cut]]:
    """Gepetto's `simplifyModel`: three consecutive joint ids of types RX/RY/RZ, the first two below 1e-5
    kg, axes pairwise not collinear, origins within 1e-4 m at the neutral configuration: the first two
    are frozen there and the third becomes a spherical joint; then `freezeJoints`."""
    data = model.createData()
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    new, frozen, last = pin.Model(), [], None
    for jid in range(model.njoints):
        vectors, masses, points = [], [], []
        for k in range(jid, min(jid + 3, model.njoints)):
            short = model.joints[k].shortname()
            column = next((i for i, c in enumerate("XYZ") if f"R{c}" in short), None)
            if column is None:
                break
            vectors.append(data.oMi[k].rotation[:, column])
            masses.append(model.inertias[k].mass)
            points.append(data.oMi[k].translation)
        if len(vectors) == 3 and masses[0] < 1e-5 and masses[1] < 1e-5:
            apart = all(np.linalg.norm(np.cross(vectors[i], vectors[j])) > 1e-6 for i, j in ((0, 1), (0, 2), (2, 1)))
            if apart and np.linalg.norm(points[0] - points[1]) < 1e-4 and np.linalg.norm(points[2] - points[1]) < 1e-4:
                last = jid
                frozen += [jid, jid + 1]
        if jid == 0:
            continue
        joint = model.joints[jid]
        if last is not None and jid == last + 2:
            joint, last = pin.JointModelSpherical(), None
        parent = new.getJointId(model.names[model.parents[jid]])
        added = new.addJoint(parent, joint, model.jointPlacements[jid], model.names[jid])
        new.appendBodyToJoint(added, model.inertias[jid], pin.SE3.Identity())
    for frame in list(model.frames)[1:]:
        new.addFrame(
            pin.Frame(frame.name, new.getJointId(model.names[frame.parentJoint]), frame.placement, frame.type), False
        )
    reduced = pin.buildReducedModel(new, frozen, pin.neutral(new))
    out = []
    for cut in cuts:
        ends = []
        for joint, place in ((cut.joint_a, cut.place_a), (cut.joint_b, cut.place_b)):
            fid = reduced.getFrameId(new.names[joint])
            if fid < reduced.nframes:
                ends.append((reduced.frames[fid].parentJoint, reduced.frames[fid].placement * place))
            else:
                ends.append((reduced.getJointId(new.names[joint]), place))
        if ends[0][0] != ends[1][0]:
            out.append(Cut(cut.name, ends[0][0], ends[0][1], ends[1][0], ends[1][1], cut.rows, cut.axis))
    return reduced, out


def urdf_mimics(urdf: Path) -> list:
    """The URDF's `<mimic>` joints as coupling records (follower = offset + multiplier x leader), read from
    its XML here (Gepetto's loader ignores them: Pinocchio's mimic=False)."""
    out = []
    for joint in ET.parse(urdf).getroot().iter("joint"):
        mimic = joint.find("mimic")
        if mimic is not None and joint.get("type") != "fixed":
            out.append(
                Coupling(
                    joint.get("name"),
                    ((joint.get("name"), 1.0),),
                    ((mimic.get("joint"), 1.0),),
                    (float(mimic.get("offset", 0)), float(mimic.get("multiplier", 1))),
                )
            )
    return out


# --- URDF+, re-read --------------------------------------------------------------------------------


def urdf_plus_load(path: Path) -> tuple[pin.Model, list[Cut], list[Coupling], list[str]]:
    """A URDF+ file read with an XML parser and Pinocchio (not mechkit's reader): Pinocchio's tree of the URDF
    (it ignores <loop> and <coupling>), each loop a cut between its links' frames moved by their <origin>,
    each coupling the sums of the joints from the two links' nearest common ancestor (generalized_rbda's K
    row), and the joints generalized_rbda takes as independent coordinates (`independent` not "false"),
    used here as motors."""
    root = ET.parse(path).getroot()
    model = pin.buildModelFromUrdf(str(path))
    parent = {j.find("child").get("link"): j for j in root.iter("joint")}
    cuts, couplings = [], []
    for loop in root.iter("loop"):
        ends = []
        for tag in ("predecessor", "successor"):
            end = loop.find(tag)
            frame = model.frames[model.getFrameId(end.get("link"), pin.FrameType.BODY)]
            origin = end.find("origin")
            xyz = (
                np.array([float(x) for x in origin.get("xyz", "0 0 0").split()]) if origin is not None else np.zeros(3)
            )
            rpy = (
                np.array([float(x) for x in origin.get("rpy", "0 0 0").split()]) if origin is not None else np.zeros(3)
            )
            ends.append((frame.parentJoint, frame.placement * pin.SE3(pin.rpy.rpyToMatrix(rpy), xyz)))
        axis = np.array([float(x) for x in loop.find("axis").get("xyz").split()])
        cuts.append(Cut(loop.get("name"), *ends[0], *ends[1], "revolute", axis))
    for coupling in root.iter("coupling"):
        paths = []
        for tag in ("predecessor", "successor"):
            path, link = [], coupling.find(tag).get("link")
            while link in parent:
                path.append(parent[link].get("name"))
                link = parent[link].find("parent").get("link")
            paths.append(path)
        pred, succ = ([(j, 1.0) for j in p if j not in set(paths[0]) & set(paths[1])] for p in paths)
        couplings.append(
            Coupling(coupling.get("name"), tuple(succ), tuple(pred), (0.0, float(coupling.find("ratio").get("value"))))
        )
    motors = [
        j.get("name") for j in root.iter("joint") if j.get("independent") != "false" and j.get("type") != "floating"
    ]
    return model, cuts, couplings, motors


# --- closure, mobility, holding ------------------------------------------------------------------------


def _value(model: pin.Model, joint: str, q: np.ndarray) -> tuple[float, int]:
    """(value, velocity index) of a one-freedom joint: its angle or position (a continuous joint's
    angle from its cos and sin)."""
    jm = model.joints[model.getJointId(joint)]
    value = np.arctan2(q[jm.idx_q + 1], q[jm.idx_q]) if jm.nq == 2 else q[jm.idx_q]
    return float(value), jm.idx_v


def _coupling_rows(model: pin.Model, couplings, q: np.ndarray) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Residuals x_f - f_ref - P(x_l - l_ref) and their Jacobian rows, for coupling records."""
    rows, jac = [], []
    for c in couplings:
        row = np.zeros(model.nv)
        x_f = 0.0
        for joint, coefficient in c.follower:
            value, iv = _value(model, joint, q)
            x_f += coefficient * value
            row[iv] += coefficient
        s_l, lead = -c.leader_ref, np.zeros(model.nv)
        for joint, coefficient in c.leader:
            value, iv = _value(model, joint, q)
            s_l += coefficient * value
            lead[iv] += coefficient
        poly = np.polynomial.Polynomial(c.polynomial)
        rows.append(np.array([x_f - c.follower_ref - poly(s_l)]))
        jac.append((row - poly.deriv()(s_l) * lead).reshape(1, -1))
    return rows, jac


def _errors(
    model: pin.Model, data: pin.Data, cuts: list[Cut], q: np.ndarray, couplings=()
) -> tuple[np.ndarray, np.ndarray]:
    """Stacked frame errors of the cuts (and coupling residuals) at q and their Jacobian (rows x nv)."""
    pin.computeJointJacobians(model, data, q)
    rows, jac = _coupling_rows(model, couplings, q)
    for c in cuts:
        oMa = data.oMi[c.joint_a] * c.place_a
        oMb = data.oMi[c.joint_b] * c.place_b
        Ja = c.place_a.inverse().action @ pin.getJointJacobian(model, data, c.joint_a, pin.ReferenceFrame.LOCAL)
        Jb = c.place_b.inverse().action @ pin.getJointJacobian(model, data, c.joint_b, pin.ReferenceFrame.LOCAL)
        position = oMa.translation - oMb.translation
        d_position = oMa.rotation @ Ja[:3] - oMb.rotation @ Jb[:3]
        if c.rows == "3d":
            rows.append(position)
            jac.append(d_position)
            continue
        aMb = oMa.inverse() * oMb
        relative = Jb - aMb.inverse().action @ Ja  # the relative twist of b from a, in frame b
        if c.rows == "6d":
            rows.append(pin.log6(aMb).vector)
            jac.append(pin.Jlog6(aMb) @ relative)
        else:  # revolute: position, and the rotation normal to the axis
            axis = c.axis / np.linalg.norm(c.axis)
            normals = np.linalg.svd(axis.reshape(1, 3))[2][1:]  # two unit vectors normal to the axis
            rows += [position, normals @ pin.log3(aMb.rotation)]
            jac += [d_position, normals @ pin.Jlog3(aMb.rotation) @ relative[3:]]
    if not rows:
        return np.zeros(0), np.zeros((0, model.nv))
    return np.concatenate(rows), np.vstack(jac)


def close(
    model: pin.Model, cuts: list[Cut], q0: np.ndarray, couplings=(), iters: int = 200
) -> tuple[np.ndarray, float]:
    """Damped least squares (Levenberg-Marquardt, damping |e|^2 + 1e-12) from q0 on the cuts' frame
    errors and the coupling residuals, until closed, or stalled at a least-squares minimum (|e| down by
    less than 1e-12 of itself in a step); returns (q, largest error component reached)."""
    data = model.createData()
    q, previous = q0.copy(), np.inf
    for _ in range(iters):
        e, J = _errors(model, data, cuts, q, couplings)
        if e.size == 0 or np.max(np.abs(e)) < CLOSURE_TOL or np.linalg.norm(e) > (1 - 1e-12) * previous:
            break
        previous = np.linalg.norm(e)
        damping = float(e @ e) + 1e-12
        q = pin.integrate(model, q, -J.T @ np.linalg.solve(J @ J.T + damping * np.eye(len(e)), e))
    e, _ = _errors(model, data, cuts, q, couplings)
    return q, float(np.max(np.abs(e))) if e.size else 0.0


def require_closed(robot: str, model: pin.Model, cuts: list[Cut], q: np.ndarray, tol: float = 1e-9) -> None:
    """Refuse a configuration whose loops are open, naming the robot, the worst cut and its error.

    Raises:
        LoopsDoNotClose: some cut keeps an error above `tol` (m, rad).
    """
    data = model.createData()
    worst = max(((float(np.max(np.abs(_errors(model, data, [c], q)[0]))), c.name) for c in cuts), default=(0.0, ""))
    if worst[0] > tol:
        raise LoopsDoNotClose(robot, worst[1], worst[0])


def _rank(matrix: np.ndarray) -> tuple[int, np.ndarray]:
    if matrix.size == 0:
        return 0, np.eye(matrix.shape[1])
    _, s, vt = np.linalg.svd(matrix)
    rank = int(np.sum(s > RANK_TOL * max(s[0], 1e-300)))
    return rank, vt[rank:].T


def study(
    model: pin.Model,
    cuts: list[Cut],
    motors: list[str],
    q0: np.ndarray | None = None,
    closure_tol: float = 1e-9,
    couplings=(),
) -> Study:
    """Close the loops from q0 (default neutral), then the DOF and the holding torques there.

    Args:
        closure_tol: the largest frame error (m, rad) a closed configuration may keep.
        couplings: coupling records (follower, leader, polynomial, follower_ref, leader_ref) as rows.
    """
    q, residual = close(model, cuts, pin.neutral(model) if q0 is None else q0, couplings)
    data = model.createData()
    _, J = _errors(model, data, cuts, q, couplings)
    rank, null = _rank(J)
    S = np.zeros((model.nv, len(motors)))
    for k, name in enumerate(motors):
        S[model.joints[model.getJointId(name)].idx_v, k] = 1.0
    undriven = null.shape[1] - _rank(S.T @ null)[0]
    g = pin.rnea(model, data, q, np.zeros(model.nv), np.zeros(model.nv))
    A = np.hstack([S, J.T])
    x, *_ = np.linalg.lstsq(A, g, rcond=None)
    gravity_residual = float(np.linalg.norm(A @ x - g) / max(np.linalg.norm(g), 1e-300))
    _, null_a = _rank(A)
    free = np.max(np.abs(null_a[: len(motors)]), axis=1, initial=0.0) if motors else np.zeros(0)
    return Study(
        q,
        residual <= closure_tol,
        residual,
        model.nv - rank,
        rank,
        undriven,
        gravity_residual < 1e-9,
        gravity_residual,
        dict(zip(motors, x[: len(motors)].tolist())),
        bool(not motors or null_a.size == 0 or np.max(np.abs(null_a[: len(motors)])) < 1e-9),
        tuple(m for m, f in zip(motors, free) if f < 1e-9),
    )


def _loop_joints(model: pin.Model, cuts: list[Cut]) -> set[int]:
    """The joints on some cut's loop: on the tree path between its two joints."""
    out = set()
    for c in cuts:
        chains = []
        for j in (c.joint_a, c.joint_b):
            chain = []
            while j > 0:
                chain.append(j)
                j = model.parents[j]
            chains.append(chain)
        out |= set(chains[0]) ^ set(chains[1])
    return out


def idle(model: pin.Model, cuts: list[Cut], q: np.ndarray, couplings=(), tol: float = 1e-9) -> dict[frozenset, int]:
    """Idle freedoms at a closed q: for each rigid body on a loop (the joints' bodies, those a 6d cut welds
    counted as one), the motions closing every cut (the null space of the frame errors' Jacobian) that
    move it alone among the bodies with mass: rank(T over the massive bodies and it) - rank(T over the
    massive bodies but it), T the world twists of the bodies' joints along those motions.

    Returns:
        {frozenset of the joint names of the body: count}, for the counts that are not zero.
    """
    group = {j: {j} for j in range(model.njoints)}
    for c in cuts:
        if c.rows == "6d":
            merged = group[c.joint_a] | group[c.joint_b]
            for j in merged:
                group[j] = merged
    _, J = _errors(model, model.createData(), cuts, q, couplings)
    _, null = _rank(J)
    data = model.createData()
    pin.computeJointJacobians(model, data, q)
    bodies = {frozenset(g) for j, g in group.items() if j > 0}
    twist = {b: pin.getJointJacobian(model, data, min(b), pin.ReferenceFrame.WORLD) @ null for b in bodies}
    heavy = {b for b in bodies if sum(model.inertias[j].mass for j in b) > 0}
    looped = {b for b in bodies if b & _loop_joints(model, cuts)}
    scale = max(1.0, max(float(np.max(np.abs(t), initial=0.0)) for t in twist.values()))

    def rank(chosen) -> int:
        return int(np.linalg.matrix_rank(np.vstack([twist[b] for b in chosen]), tol * scale)) if chosen else 0

    out = {}
    for b in looped:
        others = [o for o in heavy if o != b]
        count = rank(others + [b]) - rank(others)
        if count and null.shape[1]:
            out[frozenset(model.names[j] for j in b)] = count
    return out
