"""The closure model (what does not change: a Pinocchio tree of any joints, its loop closures and
couplings, the rows kept, the actuation) and its data (scratch: Pinocchio data, views, caches).

As in Pinocchio, the model is built once and never changes; a data is created from it for each
user of the functions (`ClosureModel.create_data`), and every function takes both.
"""

from __future__ import annotations

import copy
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache

import numpy as np
import pinocchio as pin
import scipy.linalg

from mechkit.base.exceptions import InvalidParameters, MalformedDescription
from mechkit.core import joints
from mechkit.core.coupling_rows import coupling_row
from mechkit.core.cuts import cut_rows
from mechkit.core.kernel import ClosureKernel
from mechkit.core.records import Actuator, Coupling, LoopClosure
from mechkit.core.structure import analyse, rigid_groups
from mechkit.core.tree_paths import support_columns

#: Lightest body (kg): Pinocchio's inertia sums are exact above its epsilon (2.2e-16 kg); ours, with a margin.
MIN_BODY_MASS = 1e-14


def check_depth_first(model: pin.Model) -> None:
    """Refuse a model whose joints are not numbered depth first: Pinocchio's algorithms (crba among
    them) take each joint's subtree as the velocity columns idx_v .. idx_v + nvSubtree, which only a
    depth-first numbering gives (URDF and MJCF parsers do; a model built joint by joint may not).

    Args:
        model: the Pinocchio model.

    Raises:
        MalformedDescription: the first joint whose subtree is not contiguous, by name.
    """
    for j in range(1, model.njoints):
        subtree = sorted(int(k) for k in model.subtrees[j])
        if subtree != list(range(j, j + len(subtree))):
            raise MalformedDescription(
                f"joint {model.names[j]!r}",
                "the model's joints are not numbered depth first "
                f"(its subtree is joints {subtree}): add each joint's children before its "
                "siblings, as Pinocchio's algorithms assume",
            )


def check_body_masses(model: pin.Model) -> None:
    """Refuse bodies lighter than `MIN_BODY_MASS` (massless bodies, mass 0, are fine).

    Pinocchio merges a link's inertia into its joint's body with lever = sum(m c) / max(sum m, eps),
    eps = 2.2e-16 kg, so a body of 1e-17 kg gets a centre of mass near the joint and wrong dynamics
    (the five-bar at density 1e-12 kg/m^3: accelerations 46 % off); above eps the sum is exact.

    Args:
        model: the Pinocchio model.

    Raises:
        InvalidParameters: the lightest such body, by joint name.
    """
    for j in range(1, model.njoints):
        mass = model.inertias[j].mass
        if 0.0 < mass < MIN_BODY_MASS:
            raise InvalidParameters(
                f"mass of {model.names[j]}",
                mass,
                f"below {MIN_BODY_MASS:g} kg, where Pinocchio's inertia "
                "arithmetic (an epsilon of 2.2e-16 kg) misplaces the centre of mass; scale the units",
            )


@dataclass(frozen=True)
class InputSplit:
    """Which velocity coordinates are given and which are solved for.

    Attributes:
        names: the given joints.
        input_v: (k,) their velocity indices (a ball joint gives 3, a free-flyer 6).
        free_v: (nv - k,) the other velocity indices.
    """

    names: tuple[str, ...]
    input_v: np.ndarray
    free_v: np.ndarray


class ClosureModel:
    """A Pinocchio tree with loop closures and couplings, the rows each keeps, and its actuation.

    Args:
        model: the tree (any Pinocchio joints); not copied, not changed.
        closures: the loop closures (their frames are Pinocchio frames of any type).
        couplings: coupling rows between one-freedom joints.
        actuated: the actuators in effort order: a one-freedom joint's name (a motor on it) or the
            name of one of `actuators`.
        actuators: transmissions other than one joint's motor (e.g. tendons).
        rows: None (the closures' declared rows, else the minimal rows of their loops) or "spatial"
            (every cut closed with its full rows).

    Attributes:
        model: the tree; nq, nv: its configuration and velocity sizes.
        structure: loops and Kutzbach count (`mechkit.core.structure.Structure`).
        couplings, actuators: the records it was built from.
        closures: the closures with the rows chosen. kernel: the rows kept (cuts, then couplings).
        full_kernel: every cut's full spatial rows (the physical joints), for the determinacy test.
        spatial: every cut keeps its full spatial rows (`kernel` and `full_kernel` give the same rows).
        actuated: actuator names. actuation: (na, nv) S, generalised force S^T u of efforts u.
        actuated_v: (na,) velocity indices where every actuator is one joint's motor, else None.
        unactuated: (nv, nv - rank S) orthonormal basis of the motions no actuator drives (the
            unactuated coordinates' unit vectors where every actuator is a joint motor).
        passive_v: (nv - na,) the velocity indices no motor drives where every actuator is one joint's
            motor (the columns of `unactuated`), else None.
        joint_names: tree joints (model order), then cut joints: the order of reactions.
        supports: (n_joints,) True for joints to the ground.
        massive: ids of the joints whose body has mass; on_loops: ids of the joints on a loop;
        rigid_groups: joint id -> its welded group's representative (`mechkit.core.structure.rigid_groups`).
        tracked: the two together, sorted; tracked_support: (len(tracked), nv) the velocity columns
            moving each (`mechkit.core.passive_solve.idle_count`).
        row_scale: max_i |J_i| at the neutral configuration (the closure rows' lever arm, m).
        delassus_scale: max_i |J_i|^2 / max_j M_jj there (1/kg for position rows): the unit of the
            proximal regularisation.

    Raises:
        MalformedDescription: no moving joint, a closure or coupling naming what the model lacks, joints
            not numbered depth first.
        InvalidParameters: an unknown or multi-freedom actuated joint, a body too light.
    """

    def __init__(
        self,
        model: pin.Model,
        closures: Sequence[LoopClosure],
        couplings: Sequence[Coupling] = (),
        actuated: Sequence[str] = (),
        actuators: Sequence[Actuator] = (),
        rows: str | None = None,
    ):
        if model.nv == 0:
            raise MalformedDescription(
                model.name or "model", "no joint moves (every joint is fixed): there is no mechanism to model"
            )
        check_depth_first(model)
        check_body_masses(model)
        self.model = model
        self.nq, self.nv = model.nq, model.nv
        self.structure = analyse(model, list(closures), rows, len(couplings))
        self.closures = tuple(self.structure.closures)
        cuts = [cut_rows(model, c) for c in self.closures]
        self.couplings, self.actuators = tuple(couplings), tuple(actuators)
        rows = [coupling_row(model, c) for c in self.couplings]
        self.kernel = ClosureKernel(model, cuts, rows)
        self.full_kernel = ClosureKernel(model, [cut_rows(model, c, "spatial") for c in self.closures], rows)
        self.spatial = all(c.rows == "spatial" for c in self.closures)
        self.actuated = tuple(actuated)
        self.actuation, self.actuated_v = _actuation(model, self.actuated, {a.name: a for a in actuators})
        self.unactuated = _unactuated(model, self.actuation, self.actuated_v)
        self.passive_v = _passive_v(model, self.actuated_v)
        self.joint_names = tuple(model.names[1:]) + tuple(c.name for c in self.closures)
        frames = model.frames
        self.supports = np.array(
            [model.parents[j] == 0 for j in range(1, model.njoints)]
            + [frames[c.frame_a].parentJoint == 0 or frames[c.frame_b].parentJoint == 0 for c in cuts],
            dtype=bool,
        )
        self.massive = np.array([j for j in range(1, model.njoints) if model.inertias[j].mass > 0], dtype=int)
        self.on_loops = frozenset(model.getJointId(j) for lp in self.structure.loops for j in lp.joints)
        self.rigid_groups = rigid_groups(model, list(self.closures))
        self.tracked = np.array(sorted(set(self.massive.tolist()) | self.on_loops), dtype=int)
        self.tracked_support = np.array([support_columns(model, int(j)) for j in self.tracked]).reshape(-1, model.nv)
        self.row_scale, self.delassus_scale = _scales(self)
        self._split = cache(self._make_split)

    def with_actuation(self, actuated: Sequence[str], actuators: Sequence[Actuator] = ()) -> ClosureModel:
        """The same tree, closures, couplings and rows with another actuation (e.g. every driven joint of
        a motion law).

        Args:
            actuated: the actuators in effort order: a one-freedom joint's name (a motor on it) or the
                name of one of `actuators`.
            actuators: transmissions other than one joint's motor (e.g. tendons).

        Returns:
            A shallow copy sharing the tree, kernels and structure, with the new actuation.

        Raises:
            InvalidParameters: an unknown or multi-freedom actuated joint.
        """
        out = copy.copy(self)
        out.actuated, out.actuators = tuple(actuated), tuple(actuators)
        out.actuation, out.actuated_v = _actuation(self.model, out.actuated, {a.name: a for a in actuators})
        out.unactuated = _unactuated(self.model, out.actuation, out.actuated_v)
        out.passive_v = _passive_v(self.model, out.actuated_v)
        out._split = cache(out._make_split)
        return out

    def create_data(self) -> ClosureData:
        """A new scratch data for the functions of the core."""
        return ClosureData(self)

    def joint_id(self, joint: str) -> int:
        """Pinocchio id of a joint by name.

        Args:
            joint: the joint's name.

        Returns:
            The joint's id in the Pinocchio model.

        Raises:
            InvalidParameters: no such joint.
        """
        if not isinstance(joint, str) or not self.model.existJointName(joint):
            raise InvalidParameters("joint", joint, f"no such joint; joints: {list(self.model.names[1:])}")
        return self.model.getJointId(joint)

    def split(self, names: Sequence[str]) -> InputSplit:
        """The velocity indices of the given joints and of the others (cached per tuple of names).

        Args:
            names: the given joints, in order.

        Returns:
            The names, their velocity indices `input_v` (k,) and the others `free_v` (nv - k,), read-only.

        Raises:
            InvalidParameters: no such joint (`joint_id`).
        """
        return self._split(tuple(names))

    def _make_split(self, names: tuple[str, ...]) -> InputSplit:
        given = [joints.velocity_indices(self.model, self.joint_id(j)) for j in names]
        input_v = np.concatenate(given).astype(int) if given else np.zeros(0, dtype=int)
        free = np.ones(self.nv, dtype=bool)
        free[input_v] = False
        free_v = np.flatnonzero(free)
        input_v.flags.writeable = free_v.flags.writeable = False
        return InputSplit(names, input_v, free_v)


class ClosureData:
    """Scratch of a `ClosureModel`: a Pinocchio data, views into its arrays, and derived caches.

    Attributes:
        pin: the Pinocchio data every function works in.
        J, dJ: views of `pin.J` and `pin.dJ` (6, nv).
        oMi: (njoints, 3, 4) read-only view of every joint's placement `pin.oMi`, [R | p] (world).
        f: (njoints, 6) read-only view of every joint's `pin.f` (local frame, about the joint origin).
        used: (n_used, 4, 4) scratch: homogeneous placements of the joints carrying cut frames
            (`used_placements`; a transposed view of a buffer, as `ClosureKernel.world` reads it).
        kkt_rows: the independent rows the KKT solve last used (None before the first).
        dense_plan: the gather index and basis template of `mechkit.core.dense_forward` for one `partition`.
        stress_rows: the rows of [S^T, J_full^T] `mechkit.core.determinacy.self_stresses` uses; stress_columns:
            nv of its columns, independent at the first sample, where it has full row rank there, the others
            and the permutation matrix putting them first (else None).
        split_rows: the rows of the passive block `mechkit.core.efforts.passive_one` factors, and the others.
        partition: the rows, dependent and independent columns of the closure Jacobian the null-space
            forward dynamics factors (`mechkit.core.forward`).
        inverse: the maps, views and buffers of one sample of inverse dynamics (`mechkit.core.inverse_plan`).
        settings: Pinocchio proximal settings by (mu, accuracy, max_iter), made on first use.
        legacy: Pinocchio's legacy constraints of the cuts (`mechkit.core.pin_constraints`), by method
            ("proximal", "lcaba": each needs its own Pinocchio data), made on first use.

    Raises:
        RuntimeError: Pinocchio's data does not hold its joint placements and forces as contiguous
            vectors (the layout of pin 4.1, which `oMi` and `f` view without a copy).
    """

    def __init__(self, cm: ClosureModel):
        data = cm.model.createData()
        self.pin = data
        self.J, self.dJ = data.J.reshape(6, -1), data.dJ.reshape(6, -1)  # views; Pinocchio gives (6,) when nv = 1
        placements = data.oMi.tolist()
        rotations = [M.rotation for M in placements]
        if any(_address(M.translation) != _address(R) + 9 * R.itemsize for M, R in zip(placements, rotations)):
            raise RuntimeError("Pinocchio's SE3 does not hold its translation after its rotation (pin 4.1's layout)")
        self.oMi = _stacked(rotations, (3, 4), (8, 24))
        self.f = _stacked([F.np for F in data.f.tolist()], (6,), (8,))
        self._used, n = cm.kernel.joints, cm.kernel.joints.size
        stacked = np.zeros((n, 4, 4))  # each placement transposed: `ClosureKernel.world` stacks them without a copy
        stacked[:, 3, 3] = 1.0
        self._stacked, self._flat, self.used = stacked[:, :, :3], stacked.reshape(4 * n, 4), stacked.transpose(0, 2, 1)
        self.kkt_rows: np.ndarray | None = None
        self.dense_plan: tuple | None = None
        self.legacy: dict = {}
        self.settings: dict = {}
        self.stress_rows: np.ndarray | None = None
        self.stress_columns: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        self.split_rows: tuple[np.ndarray, np.ndarray] | None = None
        self.partition: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        self.inverse = None  # `mechkit.core.inverse_plan.InversePlan`, made on first use

    def used_placements(self) -> np.ndarray:
        """`used` filled from the placements `pin.oMi` holds now (the buffer itself: copy to keep it)."""
        self.stacked_placements()
        return self.used

    def stacked_placements(self) -> np.ndarray:
        """(4 n_used, 4) the same buffer as `ClosureKernel.stacked_world` reads it, filled from `pin.oMi`."""
        self._stacked[:] = self.oMi.transpose(0, 2, 1)[self._used]
        return self._flat


def _address(x: np.ndarray) -> int:
    return x.__array_interface__["data"][0]


def _stacked(views: list[np.ndarray], shape: tuple[int, ...], strides: tuple[int, ...]) -> np.ndarray:
    """One read-only (len(views), *shape) view, element strides `strides` (bytes), over views into one
    buffer that start at equal steps (a Pinocchio std::vector): every element at once, without a copy.

    Raises:
        RuntimeError: the views do not start at equal steps (not one contiguous vector).
    """
    first = _address(views[0])
    step = _address(views[1]) - first if len(views) > 1 else 0
    if any(_address(x) != first + i * step or x.strides != strides[-x.ndim :] for i, x in enumerate(views)):
        raise RuntimeError(
            "Pinocchio's data does not hold its joint arrays as one contiguous vector (pin 4.1's layout)"
        )
    return np.lib.stride_tricks.as_strided(views[0], (len(views), *shape), (step, *strides), writeable=False)


def _actuation(
    model: pin.Model, actuated: tuple[str, ...], actuators: dict[str, Actuator]
) -> tuple[np.ndarray, np.ndarray | None]:
    """(na, nv) S and, where every actuator is one joint's motor, their velocity indices."""
    S = np.zeros((len(actuated), model.nv))
    columns: list[int] | None = []
    if len(set(actuated)) != len(actuated):
        raise InvalidParameters("actuated", actuated, "an actuator is named twice")
    for k, name in enumerate(actuated):
        terms = actuators[name].joints if name in actuators else ((name, 1.0),)
        for joint, coefficient in terms:
            if not isinstance(joint, str) or not model.existJointName(joint):
                where = "actuated" if name not in actuators else f"actuator {name!r}"
                raise InvalidParameters(where, joint, f"no such joint; joints: {list(model.names[1:])}")
            j = model.getJointId(joint)
            if model.nvs[j] != 1:
                raise InvalidParameters(
                    "actuated",
                    joint,
                    f"a {model.joints[j].shortname()} joint has {model.nvs[j]} "
                    "freedoms: a motor drives a one-freedom joint (declare an actuator transmission)",
                )
            S[k, model.joints[j].idx_v] += coefficient
        if name in actuators or columns is None:
            columns = None
        else:
            columns.append(model.joints[model.getJointId(name)].idx_v)
    return S, (None if columns is None else np.array(columns, dtype=int))


def _unactuated(model: pin.Model, S: np.ndarray, actuated_v: np.ndarray | None) -> np.ndarray:
    """(nv, nv - rank S) orthonormal basis of the motions no actuator drives."""
    if actuated_v is not None:
        return np.delete(np.eye(model.nv), actuated_v, axis=1)
    return scipy.linalg.null_space(S) if S.size else np.eye(model.nv)


def _passive_v(model: pin.Model, actuated_v: np.ndarray | None) -> np.ndarray | None:
    """The velocity indices no motor drives (increasing), or None where an actuator is not one joint's motor."""
    return None if actuated_v is None else np.delete(np.arange(model.nv), actuated_v)


def _scales(cm: ClosureModel) -> tuple[float, float]:
    """(max_i |J_i|, max_i |J_i|^2 / max_j M_jj) at the neutral configuration (1, 1 with no rows or no inertia)."""
    if cm.kernel.size == 0:
        return 1.0, 1.0
    data = cm.model.createData()
    q = pin.neutral(cm.model)
    pin.computeJointJacobians(cm.model, data, q)
    G = np.array([data.oMi[int(j)].homogeneous for j in cm.kernel.joints]).reshape(-1, 4, 4)
    _, J, _ = cm.kernel.evaluate(G, data.J, q)
    lever = float(np.sqrt(np.max(np.sum(J**2, axis=1))))
    heaviest = float(np.max(np.diag(pin.crba(cm.model, data, q))))
    delassus = lever**2 / heaviest if heaviest > 0 else 0.0
    return (lever if lever > 0 else 1.0), (delassus if delassus > 0 else 1.0)
