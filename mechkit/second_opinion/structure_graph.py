"""The structure graph of a mechanism: bodies, tree joints, cut joints, the reaction components each
joint can carry, and the actuators.

Bodies are Pinocchio's joints' child bodies (links on fixed joints merged), numbered by their joint
id; 0 is the ground. A joint's reaction (the wrench [f, m], N and N m, its parent side exerts on its
child side, world axes, moment about the joint point) lies in its constraint wrench space: the
annihilator of its motion subspace for a tree joint, the span of its full spatial rows for a cut
joint (the physical joint, whatever rows the scene solves with). Its unknown components are the
projections onto that space of chosen world unit wrenches: chosen once, at the home assembly, so that
a joint whose axis is a world axis carries world components (a pin of an x-z planar linkage: fx, fy,
fz, mx, mz), which is what lets the decomposition separate in-plane from out-of-plane equilibrium.
An actuated tree joint adds its effort: the wrench along its motion subspace.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.base.exceptions import MalformedDescription

LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
#: Singular-value threshold (relative) of the wrench spaces and of the component choice.
SPAN_TOL = 1e-9
COMPONENT_NAMES = ("fx", "fy", "fz", "mx", "my", "mz")


@dataclass(frozen=True)
class Joint:
    """One joint of the structure graph.

    Attributes:
        name: URDF joint name (tree) or `mechkit:loop` name (cut).
        parent, child: body ids (0 = ground); for a cut, frame_a's and frame_b's bodies.
        index: Pinocchio joint id (tree) or index in the closure list (cut).
        cut: whether it is a loop closure.
        components: indices (0..5 = fx fy fz mx my mz, world) of the unit wrenches whose projections
            onto the joint's constraint wrench space are its unknown reaction components.
        actuated: whether its effort (the wrench along its one-dimensional motion) is an unknown.
    """

    name: str
    parent: int
    child: int
    index: int
    cut: bool
    components: tuple[int, ...]
    actuated: bool


@dataclass(frozen=True)
class Structure:
    """Bodies and joints of a mechanism (see the module docstring).

    Attributes:
        bodies: body id -> URDF link name, moving bodies only (ids 1..njoints-1).
        joints: tree joints in Pinocchio order, then cut joints in closure order.
        parents: body id -> its parent body id in the tree (0 = ground).
    """

    bodies: dict[int, str]
    joints: tuple[Joint, ...]
    parents: dict[int, int]

    def joint(self, name: str) -> Joint:
        """The joint called ``name``.

        Args:
            name: a joint's name (tree or cut).

        Returns:
            The joint.
        """
        return next(j for j in self.joints if j.name == name)

    def chain(self, body: int) -> list[int]:
        """``body`` and its ancestors up to (not including) the ground.

        Args:
            body: a body id.

        Returns:
            Body ids, from ``body`` towards the ground.
        """
        out = []
        while body != 0:
            out.append(body)
            body = self.parents[body]
        return out

    def crossings(self, joint: Joint) -> dict[int, float]:
        """The bodies whose subtree holds exactly one side of ``joint``.

        A tree joint crosses only its child's subtree; a cut joint, the subtrees of the ancestors of
        one side that are not ancestors of the other.

        Args:
            joint: a joint of the graph.

        Returns:
            Body id -> +1 (its subtree holds the child side) or -1 (the parent side).
        """
        count: dict[int, float] = {}
        for body, sign in ((joint.child, 1.0), (joint.parent, -1.0)):
            for k in self.chain(body):
                count[k] = count.get(k, 0.0) + sign
        return {k: s for k, s in count.items() if s != 0.0}


@dataclass(frozen=True)
class Cuts:
    """The cuts' full spatial rows at one configuration: the kernel and its row wrenches (rows, 6),
    world axes, each moment about its cut's point p_b (m)."""

    kernel: core.ClosureKernel
    wrenches: np.ndarray


def cut_wrenches(cm: core.ClosureModel, cd: core.ClosureData, q: np.ndarray) -> Cuts:
    """The full rows' wrenches of every cut at a configuration, moments about each cut's frame_b origin.

    Args:
        cm: the closure model.
        cd: a data of it.
        q: an assembled configuration (nq,).

    Returns:
        The cuts' kernel and their row wrenches (full rows, 6), world axes.
    """
    G, _, _ = core.kinematic_pass(cm, cd, q[None])
    kernel = cm.full_kernel
    W = kernel.row_wrenches(G[0])
    points = kernel.cut_points(G[0])
    for c, rows in enumerate(kernel.cut_slices):
        W[rows, 3:] -= np.cross(points[c], W[rows, :3])
    return Cuts(kernel, W)


def _orthonormal(span: np.ndarray) -> np.ndarray:
    """Orthonormal basis (6, r) of the column span of ``span``."""
    if span.size == 0:
        return np.zeros((6, 0))
    u, s, _ = np.linalg.svd(span, full_matrices=False)
    return u[:, : int(np.sum(s > SPAN_TOL * max(s[0], 1e-300)))]


def tree_motion(model: pin.Model, data: pin.Data, joint: int) -> np.ndarray:
    """The motion subspace of a tree joint, world axes, linear part at the joint origin.

    Needs `pin.computeJointJacobians` at the configuration.

    Args:
        model: the Pinocchio model.
        data: its data, joint Jacobians current.
        joint: the joint's id.

    Returns:
        (6, nv_j) motion subspace.
    """
    jm = model.joints[joint]
    return pin.getJointJacobian(model, data, joint, LWA).reshape(6, -1)[:, jm.idx_v : jm.idx_v + jm.nv]


def constraint_span(model: pin.Model, data: pin.Data, cuts: Cuts, joint: Joint) -> np.ndarray:
    """Orthonormal basis (6, r) of the joint's constraint wrench space at the current configuration.

    World axes, moment about the joint point (tree: joint origin; cut: frame_b's origin): for a cut,
    the span of its full rows' wrenches from the closure kernel. Needs joint Jacobians current.

    Args:
        model: the Pinocchio model.
        data: its data, joint Jacobians current.
        cuts: the cuts' full rows (`cut_wrenches`).
        joint: the joint.

    Returns:
        The basis (6, r).
    """
    if not joint.cut:
        motion = tree_motion(model, data, joint.index)
        return _orthonormal(np.eye(6) - motion @ np.linalg.pinv(motion))
    return _orthonormal(cuts.wrenches[cuts.kernel.cut_slices[joint.index]].T)


def choose_components(span: np.ndarray) -> tuple[int, ...]:
    """World unit wrenches whose projections onto ``span`` form a basis of it, aligned ones first.

    Args:
        span: an orthonormal basis (6, r) of a constraint wrench space.

    Returns:
        The chosen world wrench directions (indices 0-5: fx, fy, fz, mx, my, mz), r of them, sorted.
    """
    projections = span @ span.T
    order = np.argsort(-np.linalg.norm(projections, axis=0), kind="stable")
    chosen: list[int] = []
    for k in order:
        trial = chosen + [int(k)]
        if np.linalg.matrix_rank(projections[:, trial], tol=1e-6) == len(trial):
            chosen = trial
        if len(chosen) == span.shape[1]:
            break
    return tuple(sorted(chosen))


def body_names(model: pin.Model) -> dict[int, str]:
    """Body id -> name of the URDF link carried by that Pinocchio joint (its first body frame).

    Args:
        model: the Pinocchio model.

    Returns:
        Body id -> link name (the joint's name where no body frame names it).
    """
    names = {}
    for frame in model.frames:
        if frame.type == pin.FrameType.BODY and frame.parentJoint > 0:
            names.setdefault(int(frame.parentJoint), frame.name)
    return {j: names.get(j, model.names[j]) for j in range(1, model.njoints)}


def build_structure(cm: core.ClosureModel, q: np.ndarray) -> Structure:
    """The structure graph of a closure model, components chosen at the (assembled) configuration ``q``.

    Args:
        cm: the closure model (its actuation and full cut rows).
        q: an assembled configuration (nq,).

    Returns:
        The structure graph.

    Raises:
        MalformedDescription: an actuated joint does not have exactly one degree of freedom.
    """
    model, actuated = cm.model, cm.actuated
    data = model.createData()
    full_rows = cut_wrenches(cm, cm.create_data(), q)
    pin.computeJointJacobians(model, data, q)
    joints: list[Joint] = []
    for j in range(1, model.njoints):
        name = model.names[j]
        if name in actuated and model.joints[j].nv != 1:
            raise MalformedDescription(f"joint {name!r}", "an actuator needs a one-DOF joint")
        probe = Joint(name, int(model.parents[j]), j, j, False, (), name in actuated)
        span = constraint_span(model, data, full_rows, probe)
        joints.append(Joint(name, probe.parent, j, j, False, choose_components(span), probe.actuated))
    for c, cut in enumerate(cm.full_kernel.cuts):
        probe = Joint(
            cut.closure.name,
            int(model.frames[cut.frame_a].parentJoint),
            int(model.frames[cut.frame_b].parentJoint),
            c,
            True,
            (),
            False,
        )
        span = constraint_span(model, data, full_rows, probe)
        joints.append(Joint(probe.name, probe.parent, probe.child, c, True, choose_components(span), False))
    return Structure(body_names(model), tuple(joints), {j: int(model.parents[j]) for j in range(1, model.njoints)})
