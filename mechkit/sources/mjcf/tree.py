"""The tree of a compiled MuJoCo model as a Pinocchio model, its coordinates MuJoCo's.

Each MuJoCo joint is one Pinocchio joint (hinge -> revolute, slide -> prismatic, ball -> spherical,
free -> free-flyer), placed so that Pinocchio's q equals MuJoCo's qpos: a hinge or slide is zero at
q = 0 where MuJoCo's is at qpos0 (`ref`), its frame at the joint's anchor `pos`; a ball's quaternion is
MuJoCo's (reordered x, y, z, w); a free joint's q is the body's world position and orientation.
Several joints in one body are a chain through the joints' frames. Each body's inertia is the one
MuJoCo compiled (from `<inertial>`, or inferred from its geoms and meshes), body frames are BODY
frames, sites OP_FRAMEs; armature goes to `model.armature`, a limited hinge's or slide's `range` to
the model's position limits (else they stay unbounded), the gravity to `model.gravity` (zero where
`<flag gravity="disable">`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin
from numpy.typing import ArrayLike

from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.physical import check_body
from mechkit.sources.pinocchio_tree import add_body, add_frame, add_joint, joint_model

if TYPE_CHECKING:
    from types import ModuleType

    from mujoco import MjModel

#: MuJoCo joint type (mjtJoint) -> the Pinocchio joint kind.
KINDS = {0: "free", 1: "spherical", 2: "prismatic", 3: "revolute"}


@dataclass(frozen=True)
class Tree:
    """A compiled MuJoCo model's tree in Pinocchio.

    Attributes:
        model: the Pinocchio model.
        names: object kind ("body", "joint", "site", "equality", "tendon", "actuator") -> names by
            MuJoCo id (an unnamed object is `<kind><id>`).
        body_joint: MuJoCo body id -> the Pinocchio joint that carries it (0: the world).
        body_placement: MuJoCo body id -> its frame in that joint's frame.
        world: MuJoCo body id -> its frame in the world at qpos0.
    """

    model: pin.Model
    names: dict[str, list[str]]
    body_joint: list[int]
    body_placement: list[pin.SE3]
    world: list[pin.SE3]

    def joint_index(self, name: str) -> int:
        """The MuJoCo id of a joint by name.

        Args:
            name: the joint's name.

        Returns:
            Its MuJoCo id.
        """
        return self.names["joint"].index(name)


def se3(quat_wxyz: ArrayLike, pos: ArrayLike) -> pin.SE3:
    """The placement of a MuJoCo (quaternion w, x, y, z; position) pair.

    Args:
        quat_wxyz: unit quaternion (w, x, y, z).
        pos: position (3,), m.

    Returns:
        The placement.
    """
    w, x, y, z = (float(c) for c in quat_wxyz)
    return pin.SE3(pin.Quaternion(w, x, y, z).normalized().matrix(), np.asarray(pos, dtype=float))


def object_names(mujoco: ModuleType, mm: MjModel) -> dict[str, list[str]]:
    """Names of MuJoCo's bodies, joints, sites, equalities, tendons and actuators (see `Tree.names`); an
    unnamed object is called <kind><id>.

    Args:
        mujoco: the mujoco module.
        mm: the compiled model.

    Returns:
        Kind -> names in MuJoCo's id order (body 0 is "world").

    Raises:
        MalformedDescription: two objects of one kind share a name.
    """
    obj = mujoco.mjtObj
    kinds = {
        "body": (obj.mjOBJ_BODY, mm.nbody),
        "joint": (obj.mjOBJ_JOINT, mm.njnt),
        "site": (obj.mjOBJ_SITE, mm.nsite),
        "equality": (obj.mjOBJ_EQUALITY, mm.neq),
        "tendon": (obj.mjOBJ_TENDON, mm.ntendon),
        "actuator": (obj.mjOBJ_ACTUATOR, mm.nu),
    }
    out = {}
    for kind, (code, count) in kinds.items():
        out[kind] = [mujoco.mj_id2name(mm, code, i) or f"{kind}{i}" for i in range(count)]
        taken = set()
        for name in out[kind]:
            if name in taken:
                raise MalformedDescription(
                    f"MJCF {kind} {name!r}", f"two {kind}s of that name (an unnamed one is called <{kind}><id>)"
                )
            taken.add(name)
    out["body"][0] = "world"
    return out


def build_tree(mujoco: ModuleType, mm: MjModel, name: str) -> Tree:
    """The Pinocchio tree of a compiled MuJoCo model (see the module docstring).

    Args:
        mujoco: the mujoco module.
        mm: the compiled model.
        name: the model's name.

    Returns:
        The tree: the Pinocchio model (q = MuJoCo's qpos), MuJoCo's names, and where each MuJoCo body is.

    Raises:
        MalformedDescription: a body with gravity compensation (not read), a duplicate name.
    """
    names = object_names(mujoco, mm)
    model = pin.Model()
    model.name = name
    gravity = not mm.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_GRAVITY
    model.gravity = pin.Motion(np.asarray(mm.opt.gravity, dtype=float) * gravity, np.zeros(3))
    add_body(model, "world", 0, pin.SE3.Identity(), pin.Inertia.Zero())
    body_joint, placement, world = [0], [pin.SE3.Identity()], [pin.SE3.Identity()]
    for b in range(1, mm.nbody):
        if float(mm.body_gravcomp[b]) != 0.0:
            raise MalformedDescription(f"MJCF body {names['body'][b]!r}", "gravity compensation (gravcomp) is not read")
        parent = int(mm.body_parentid[b])
        offset = se3(mm.body_quat[b], mm.body_pos[b])
        world.append(world[parent] * offset)
        joint, at = body_joint[parent], placement[parent] * offset
        for j in range(int(mm.body_jntadr[b]), int(mm.body_jntadr[b]) + int(mm.body_jntnum[b])):
            joint, at = _joint(model, mm, names["joint"][j], j, joint, at)
        body_joint.append(joint)
        placement.append(at)
        principal = _principal(mm.body_iquat[b], mm.body_inertia[b])
        principal = check_body(f"MJCF body {names['body'][b]!r}", float(mm.body_mass[b]), principal, principal.tolist())
        inertia = pin.Inertia(float(mm.body_mass[b]), np.asarray(mm.body_ipos[b], dtype=float), principal)
        add_body(model, names["body"][b], joint, at, inertia)
    for s in range(mm.nsite):
        b = int(mm.site_bodyid[s])
        add_frame(model, names["site"][s], body_joint[b], placement[b] * se3(mm.site_quat[s], mm.site_pos[s]))
    return Tree(model, names, body_joint, placement, world)


def _principal(iquat: ArrayLike, diagonal: ArrayLike) -> np.ndarray:
    """The rotational inertia (kg m^2, about the centre of mass, body frame) from MuJoCo's principal form."""
    R = se3(iquat, np.zeros(3)).rotation
    return R @ np.diag(np.asarray(diagonal, dtype=float)) @ R.T


def _joint(model: pin.Model, mm: MjModel, name: str, j: int, parent: int, at: pin.SE3) -> tuple[int, pin.SE3]:
    """Add MuJoCo joint j after the frame `at` (in parent's frame); returns (joint id, body frame in it)."""
    kind = KINDS[int(mm.jnt_type[j])]
    axis = np.asarray(mm.jnt_axis[j], dtype=float)
    pos = np.asarray(mm.jnt_pos[j], dtype=float)
    ref = float(mm.qpos0[mm.jnt_qposadr[j]])
    if kind == "revolute":
        placement, body = at * pin.SE3(pin.exp3(-ref * axis), pos), pin.SE3(np.eye(3), -pos)
    elif kind == "prismatic":
        placement, body = at * pin.SE3(np.eye(3), -ref * axis), pin.SE3.Identity()
    elif kind == "spherical":
        placement, body = at * pin.SE3(np.eye(3), pos), pin.SE3(np.eye(3), -pos)
    else:  # free: MuJoCo allows it only in a child of the world; q is the body's world pose
        placement, body = pin.SE3.Identity(), pin.SE3.Identity()
    jid = add_joint(model, name, parent, joint_model(kind, axis), placement)
    dof, nv = int(mm.jnt_dofadr[j]), model.joints[jid].nv
    model.armature[model.joints[jid].idx_v : model.joints[jid].idx_v + nv] = mm.dof_armature[dof : dof + nv]
    if kind in ("revolute", "prismatic") and mm.jnt_limited[j]:
        iq = model.joints[jid].idx_q
        model.lowerPositionLimit[iq], model.upperPositionLimit[iq] = (float(x) for x in mm.jnt_range[j])
    return jid, body
