"""The structure of a mechanism from its topology: loops, the Kutzbach count, sub-mechanisms, idle freedoms.

Each cut closes one fundamental loop: the cut joint and the tree joints on the path between its two
frames. A loop is

- planar when every revolute axis on it (tree and cut) is parallel to one normal n and every
  prismatic axis is normal to n: its bodies move in parallel planes, its motion space has
  lambda = 3 dimensions;
- spherical when every axis on it passes through one point c and it has no prismatic joint:
  lambda = 3;
- spatial otherwise: lambda = 6.

Kutzbach-Gruebler count, loop by loop: M = sum of the tree joints' freedoms (nv) + sum of the cut
joints' freedoms within their loop's motion space - sum of lambda - one per coupling row. A cut
declared without `rows` is closed with the minimal rows of its loop (planar: 2 position rows normal
to n, or 3 for a weld; spherical: 2 rotation rows for a revolute cut, 1 for a Hooke, 3 for a weld);
`rows="spatial"` forces the full rows. The geometry is read at the neutral configuration: parallel
axes stay parallel under planar motion, and axes through the centre stay through it under spherical
motion.

Idle freedoms: velocities that close every loop (J v = 0) yet move one body on a loop and no other
body with mass (a rod spinning about its own axis between two spherical joints).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import pinocchio as pin
import scipy.linalg

from mechkit.base.exceptions import MalformedDescription
from mechkit.core.records import LoopClosure

#: Tolerance (rad, and m relative to the loop's size) of the parallel / concurrent axis tests.
GEOMETRY_TOL = 1e-9
#: Rows of each cut kind with rows="spatial" (a free body has 6 freedoms, the cut joint leaves f).
FULL_ROWS = {"revolute": 5, "prismatic": 5, "spherical": 3, "hooke": 4, "weld": 6}
#: Freedoms of each cut kind within a planar / spherical / spatial loop's motion space.
CUT_FREEDOMS = {
    "planar": {"revolute": 1, "prismatic": 1, "spherical": 1, "hooke": 1, "weld": 0},
    "spherical": {"revolute": 1, "prismatic": 0, "spherical": 3, "hooke": 2, "weld": 0},
    "spatial": {"revolute": 1, "prismatic": 1, "spherical": 3, "hooke": 2, "weld": 0},
}
#: Minimal rows of a cut kind in a planar / spherical loop (absent: the full rows are kept).
MINIMAL_ROWS = {
    "planar": {"revolute": 2, "spherical": 2, "weld": 3},
    "spherical": {"revolute": 2, "hooke": 1, "weld": 3},
}
MOTION_DIM = {"planar": 3, "spherical": 3, "spatial": 6}


@dataclass(frozen=True)
class Loop:
    """One fundamental loop.

    Attributes:
        cut: the cut joint's name.
        joints: tree joints on the loop, from frame_a's body down to frame_b's.
        kind: "planar", "spherical" or "spatial".
        motion_dim: lambda, the dimension of the loop's motion space (3 or 6).
        cut_freedoms: the cut joint's freedoms within that space.
        full_rows: rows of the cut with rows="spatial"; rows: rows it is closed with.
        chosen: "declared" (the file names the rows), "detected" (minimal rows of the loop) or
            "forced" (rows="spatial" asked).
    """

    cut: str
    joints: tuple[str, ...]
    kind: str
    motion_dim: int
    cut_freedoms: int
    full_rows: int
    rows: int
    chosen: str


@dataclass(frozen=True)
class Structure:
    """Topology of a mechanism: its loops, closures (with the rows chosen) and Kutzbach count."""

    loops: tuple[Loop, ...]
    closures: tuple[LoopClosure, ...]
    tree_freedoms: int
    couplings: int = 0

    @property
    def kutzbach(self) -> int:
        """M = nv + sum of cut freedoms - sum of lambda (loop by loop) - one per coupling row."""
        return self.tree_freedoms + sum(lp.cut_freedoms - lp.motion_dim for lp in self.loops) - self.couplings

    @property
    def rows_avoided(self) -> int:
        """Rows the sub-mechanism detection (or the declarations) saved against the full spatial rows."""
        return sum(lp.full_rows - lp.rows for lp in self.loops)


def joint_axis(model: pin.Model, data: pin.Data, joint: int) -> tuple[str, np.ndarray | None]:
    """The kind and axis of a tree joint.

    Read from the joint's motion subspace (its column of the LOCAL joint Jacobian), so that every
    revolute or prismatic joint model (aligned, unaligned, unbounded) is recognised alike.

    Args:
        model: the Pinocchio model.
        data: its data, after `pin.computeJointJacobians`.
        joint: Pinocchio joint id.

    Returns:
        "revolute", "prismatic" or "other", and the unit axis (3,) in the joint frame (None for "other").
    """
    if model.nvs[joint] != 1:
        return "other", None
    J = pin.getJointJacobian(model, data, joint, pin.ReferenceFrame.LOCAL).reshape(6, -1)
    S = J[:, model.joints[joint].idx_v]  # [linear; angular], joint frame
    linear, angular = S[:3], S[3:]
    if np.linalg.norm(linear) < GEOMETRY_TOL and np.linalg.norm(angular) > 0:
        return "revolute", angular / np.linalg.norm(angular)
    if np.linalg.norm(angular) < GEOMETRY_TOL and np.linalg.norm(linear) > 0:
        return "prismatic", linear / np.linalg.norm(linear)
    return "other", None


def body_name(model: pin.Model, joint: int) -> str:
    """The URDF link a joint carries.

    Args:
        model: the Pinocchio model.
        joint: Pinocchio joint id.

    Returns:
        The name of the first BODY frame on the joint at identity placement, else the joint's name.
    """
    for frame in model.frames:
        if frame.parentJoint == joint and frame.type == pin.FrameType.BODY and frame.placement.isIdentity():
            return frame.name
    return model.names[joint]


def loop_joints(model: pin.Model, joint_a: int, joint_b: int) -> list[int]:
    """Tree joints on the path between two bodies (through their common ancestor).

    Args:
        model: the Pinocchio model.
        joint_a: Pinocchio id of the joint carrying the first body.
        joint_b: Pinocchio id of the joint carrying the second body.

    Returns:
        Joint ids from joint_a up to (not including) the common ancestor, then down to joint_b.
    """

    def chain(j: int) -> list[int]:
        out = []
        while j > 0:
            out.append(j)
            j = model.parents[j]
        return out

    a, b = chain(joint_a), chain(joint_b)
    return [j for j in a if j not in b] + [j for j in reversed(b) if j not in a]


def analyse(model: pin.Model, closures: list[LoopClosure], rows: str | None = None, couplings: int = 0) -> Structure:
    """Classify every loop, choose the rows of the cuts declared without rows, count the freedoms.

    The geometry is read at the neutral configuration.

    Args:
        model: the Pinocchio tree.
        closures: the loop closures (one cut each).
        rows: None (declared rows, minimal rows where none are declared) or "spatial" (every cut
            closed with its full rows).
        couplings: the number of coupling rows (each takes one freedom).

    Returns:
        The loops (kind, motion space, rows chosen), the closures with their rows set, and the counts
        for the Kutzbach formula.

    Raises:
        MalformedDescription: a cut whose frames are not in the model or sit on one body.
    """
    data = model.createData()
    q0 = pin.neutral(model)
    pin.computeJointJacobians(model, data, q0)
    pin.framesForwardKinematics(model, data, q0)
    axes = {j: joint_axis(model, data, j) for j in range(1, model.njoints)}
    loops, out = [], []
    for closure in closures:
        ids = []
        for frame in (closure.frame_a, closure.frame_b):
            if not model.existFrame(frame):
                raise MalformedDescription(f"mechkit:loop {closure.name!r}", f"frame {frame!r} not in the model")
            ids.append(model.getFrameId(frame))
        ja, jb = (model.frames[i].parentJoint for i in ids)
        if ja == jb:
            raise MalformedDescription(
                f"mechkit:loop {closure.name!r}", f"frames {closure.frame_a!r} and {closure.frame_b!r} are on one body"
            )
        path = loop_joints(model, ja, jb)
        kind, normal = _classify(data, [(j, *axes[j]) for j in path], closure, ids)
        closure, chosen = _choose_rows(closure, kind, normal, data.oMf[ids[0]].rotation, rows)
        full = FULL_ROWS[closure.kind]
        kept = full if closure.rows == "spatial" else MINIMAL_ROWS[closure.rows][closure.kind]
        loops.append(
            Loop(
                closure.name,
                tuple(model.names[j] for j in path),
                kind,
                MOTION_DIM[kind],
                CUT_FREEDOMS[kind][closure.kind],
                full,
                kept,
                chosen,
            )
        )
        out.append(closure)
    return Structure(tuple(loops), tuple(out), model.nv, couplings)


def _lines(data, path, closure, ids) -> tuple[list, list, bool]:
    """World (point, axis) of the loop's revolute and prismatic axes; False if another joint is on it."""
    revolute, prismatic, simple = [], [], True
    for j, kind, axis in path:
        M = data.oMi[j]
        if kind == "other":
            simple = False
        else:
            (revolute if kind == "revolute" else prismatic).append((M.translation.copy(), M.rotation @ axis))
    oMa, oMb = data.oMf[ids[0]], data.oMf[ids[1]]
    if closure.kind in ("revolute", "prismatic"):
        (revolute if closure.kind == "revolute" else prismatic).append(
            (oMa.translation.copy(), oMa.rotation @ closure.axis)
        )
    elif closure.kind == "hooke":
        revolute += [
            (oMa.translation.copy(), oMa.rotation @ closure.axis_a),
            (oMb.translation.copy(), oMb.rotation @ closure.axis_b),
        ]
    return revolute, prismatic, simple


def _classify(data, path, closure, ids) -> tuple[str, np.ndarray | None]:
    """("planar", normal) | ("spherical", centre) | ("spatial", None); path: (joint, kind, axis)."""
    revolute, prismatic, simple = _lines(data, path, closure, ids)
    if not simple or not revolute:
        return "spatial", None
    n = revolute[0][1] / np.linalg.norm(revolute[0][1])
    if all(np.linalg.norm(np.cross(a, n)) < GEOMETRY_TOL for _, a in revolute) and all(
        abs(a @ n) < GEOMETRY_TOL for _, a in prismatic
    ):
        return "planar", n
    if prismatic:
        return "spatial", None
    # the point closest to every revolute line (least squares), then every line must pass through it
    A = sum(np.eye(3) - np.outer(a, a) for _, a in revolute)
    b = sum((np.eye(3) - np.outer(a, a)) @ p for p, a in revolute)
    if np.linalg.matrix_rank(A, 1e-9) < 3:
        return "spatial", None
    c = np.linalg.solve(A, b)
    size = max(1.0, max(np.linalg.norm(p - c) for p, _ in revolute))
    if all(np.linalg.norm(np.cross(c - p, a)) < GEOMETRY_TOL * size for p, a in revolute):
        if (
            closure.kind in ("spherical", "hooke")
            and np.linalg.norm(data.oMf[ids[0]].translation - c) > GEOMETRY_TOL * size
        ):
            return "spatial", None
        return "spherical", c
    return "spatial", None


def _choose_rows(closure: LoopClosure, kind: str, normal, Ra: np.ndarray, rows: str | None) -> tuple[LoopClosure, str]:
    if rows == "spatial":
        return replace(closure, rows="spatial"), "forced"
    if closure.explicit_rows:
        return closure, "declared"
    if closure.kind not in MINIMAL_ROWS.get(kind, {}):
        return replace(closure, rows="spatial"), "detected"
    axis = closure.axis
    if kind == "planar" and closure.kind != "revolute":
        axis = Ra.T @ normal
    return replace(closure, rows=kind, axis=axis), "detected"


def rigid_groups(model: pin.Model, closures: list[LoopClosure]) -> dict[int, int]:
    """The rigid groups of bodies: bodies a weld closure joins move as one body (a rod split in two halves
    welded at its middle, as Gepetto's files write a rod between two balls).

    Args:
        model: the Pinocchio model.
        closures: the loop closures (the welds among them join bodies).

    Returns:
        Joint id -> the id representing its rigid group (the smallest id of the group), for every joint.
    """
    parent = {j: j for j in range(model.njoints)}

    def find(j: int) -> int:
        while parent[j] != j:
            parent[j] = parent[parent[j]]
            j = parent[j]
        return j

    for c in closures:
        if c.kind == "weld":
            a, b = (find(model.frames[model.getFrameId(f)].parentJoint) for f in (c.frame_a, c.frame_b))
            parent[max(a, b)] = min(a, b)
    return {j: find(j) for j in range(model.njoints)}


def idle_counts(
    twists: dict[int, np.ndarray], massive: set[int], on_loops: set[int], tol: float = 1e-9
) -> dict[int, int]:
    """Per body on a loop, how many of a set of velocity modes move it alone: no other body with mass.

    count(b) = rank(T over the massive bodies and b) - rank(T over the massive bodies but b), T the
    stacked world twists along the modes: a rod spinning about its own axis between two balls counts
    for the rod, with mass or without. Bodies welded together (`rigid_groups`) are one body: give one
    twist per group, keyed by its representative, with the group's mass and loop membership.

    Args:
        twists: joint id -> (6, d) world twists of its body along the d modes, for every body with mass
            and every body on a loop.
        massive: ids of the bodies with mass.
        on_loops: ids of the bodies on a loop.
        tol: rank tolerance, relative to the largest twist entry (at least 1).

    Returns:
        joint id -> count, for the bodies on loops with a non-zero count.
    """
    if not twists:
        return {}
    d = next(iter(twists.values())).shape[1]
    scale = max(1.0, max(float(np.max(np.abs(t), initial=0.0)) for t in twists.values()))

    def rank(joints: list[int]) -> int:
        return int(np.linalg.matrix_rank(np.vstack([twists[j] for j in joints]), tol * scale)) if joints else 0

    out = {}
    for b in sorted(on_loops & set(twists)):
        others = [k for k in massive if k != b and k in twists]
        count = rank(others + [b]) - rank(others)
        if count and d:
            out[b] = count
    return out


def grouped(
    twists: dict[int, np.ndarray], massive: set[int], on_loops: set[int], groups: dict[int, int]
) -> tuple[dict[int, np.ndarray], set[int], set[int]]:
    """The arguments of `idle_counts` with one entry per rigid group (`rigid_groups`).

    Args:
        twists: joint id -> (6, d) world twists of its body along the modes.
        massive: ids of the bodies with mass.
        on_loops: ids of the bodies on a loop.
        groups: joint id -> its group's representative (`rigid_groups`).

    Returns:
        The twists by group (any member's: welded bodies share one), the groups with mass, and the
        groups on a loop.
    """
    out: dict[int, np.ndarray] = {}
    for j, t in twists.items():
        out.setdefault(groups[j], t)
    return out, {groups[j] for j in massive}, {groups[j] for j in on_loops}


def idle_freedoms(
    model: pin.Model, q: np.ndarray, jacobian: np.ndarray, on_loops: set[int], groups: dict[int, int], tol: float = 1e-9
) -> dict[str, int]:
    """Idle freedoms at q: body (the URDF link a joint carries) -> how many velocity modes move it alone.

    A mode is a v with J v = 0; it is idle for body k on a loop when no other body with mass moves
    (`idle_counts`, over the null space of J).

    Args:
        model: the Pinocchio model.
        q: (nq,) assembled configuration.
        jacobian: the closure Jacobian at q (rows, nv).
        on_loops: joint ids of the bodies that are on some loop.
        groups: `rigid_groups` of the closures.
        tol: relative tolerance of the null space of J (rcond) and of the ranks (`idle_counts`).

    Returns:
        Body name (`body_name`) -> number of idle modes, for the bodies that have any.
    """
    null = scipy.linalg.null_space(jacobian, rcond=tol) if jacobian.size else np.eye(model.nv)
    if null.shape[1] == 0:
        return {}
    data = model.createData()
    pin.computeJointJacobians(model, data, q)
    massive = {j for j in range(1, model.njoints) if model.inertias[j].mass > 0}
    twists = {
        j: pin.getJointJacobian(model, data, j, pin.ReferenceFrame.WORLD).reshape(6, -1) @ null
        for j in massive | on_loops
    }
    twists, heavy, looped = grouped(twists, massive, on_loops, groups)
    return {body_name(model, j): n for j, n in idle_counts(twists, heavy, looped, tol).items()}
