"""An MJCF (MuJoCo) file: compiled by MuJoCo, written back as a tree URDF with `<mechkit:loop>`s.

MuJoCo resolves the format (defaults, angle units, orientations, inertias from geoms); this module
reads the compiled model at its reference configuration qpos0:

- each body -> a URDF link; its hinge / slide joints -> revolute / prismatic joints (several joints
  in one body -> a chain through massless links), zero at MuJoCo's qpos0 = `ref`, so the joint
  coordinates equal MuJoCo's qpos; a body without joints is fixed to its parent; ball and free
  joints have no URDF counterpart (a `MalformedDescription`);
- sites -> frames (fixed links);
- `<equality>`: `connect` -> a spherical cut at the anchor (body 2's side at the same world point
  at qpos0), two `connect`s between the same two bodies at distinct points -> one revolute cut about
  the line through them, `weld` -> a weld cut at body 2's frame (relative pose taken at qpos0);
- joint actuators -> actuated joints; home inputs and guess: qpos0.

Not read: the MJCF's gravity (mechkit's is -9.81 m/s^2 along z), joint springs and damping,
contacts, and the solver parameters of the equalities (mechkit's loops are exact).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription, MethodUnavailable
from mechkit.sources.description import Description, read_text
from mechkit.sources.urdf import LOOP_NAMESPACE, describe_urdf, parse_xml

CONNECT, WELD = 0, 1  # mjtEq
HINGE, SLIDE = 3, 2  # mjtJoint
SITE = 6  # mjtObj
TRN_JOINT = 0  # mjtTrn


def read_mjcf(path: Path) -> Description:
    """The description in an MJCF file (see the module docstring).

    Raises:
        MethodUnavailable: MuJoCo is not installed (`pip install mechkit[peers]`).
        MalformedDescription: not MJCF, MuJoCo cannot compile it, or it uses what a URDF tree
            cannot hold (ball / free joints, tendon actuators, joint or tendon equalities).
    """
    root = parse_xml(read_text(path), str(path))
    if root.tag != "mujoco":
        raise MalformedDescription(str(path), f"root element <{root.tag}>: an MJCF file starts with <mujoco>")
    try:
        import mujoco
    except ImportError:
        raise MethodUnavailable("MJCF reading", "needs MuJoCo: pip install 'mechkit[peers]'") from None
    try:
        mm = mujoco.MjModel.from_xml_path(str(path))
    except ValueError as err:
        raise MalformedDescription(str(path), f"MuJoCo could not compile it: {str(err).splitlines()[0]}") from None
    md = mujoco.MjData(mm)
    mujoco.mj_kinematics(mm, md)
    writer = _Writer(mujoco, mm, md, root.get("model") or path.name.split(".")[0])
    urdf = writer.text()
    base = describe_urdf(urdf, path, "mjcf")
    qpos0 = {writer.joint_name(j): float(mm.qpos0[mm.jnt_qposadr[j]]) for j in range(mm.njnt)}
    actuated = writer.actuated()
    return Description(base.name, urdf, actuated, {j: qpos0[j] for j in actuated}, qpos0, path, "mjcf")


def _fmt(values) -> str:
    return " ".join(repr(float(x)) for x in np.ravel(values))


def _se3(quat_wxyz, pos) -> pin.SE3:
    w, x, y, z = (float(c) for c in quat_wxyz)
    return pin.SE3(pin.Quaternion(w, x, y, z).normalized().matrix(), np.asarray(pos, dtype=float))


class _Writer:
    """URDF text of a compiled MuJoCo model (one pass over the bodies, in MuJoCo's order)."""

    def __init__(self, mujoco, mm, md, name: str):
        self.obj, self.id2name = mujoco.mjtObj, mujoco.mj_id2name
        self.mm, self.md, self.name = mm, md, name
        self.world = [pin.SE3(md.xmat[b].reshape(3, 3).copy(), md.xpos[b].copy()) for b in range(mm.nbody)]
        self.offset = {0: pin.SE3.Identity()}  # URDF link frame -> MuJoCo body frame
        self.parts: list[str] = []
        self.link_line: dict[str, int] = {}  # link name -> its index in parts

    def _name(self, kind, i: int, prefix: str) -> str:
        return self.id2name(self.mm, kind, i) or f"{prefix}{i}"

    def body_name(self, b: int) -> str:
        return "world" if b == 0 else self._name(self.obj.mjOBJ_BODY, b, "body")

    def joint_name(self, j: int) -> str:
        return self._name(self.obj.mjOBJ_JOINT, j, "joint")

    def text(self) -> str:
        self.parts = [f'<robot name="{self.name}" xmlns:mechkit="{LOOP_NAMESPACE}">', '  <link name="world"/>']
        for b in range(1, self.mm.nbody):
            self._body(b)
        self._equalities()
        self.parts.append("</robot>")
        return "\n".join(self.parts) + "\n"

    def _link(self, name: str) -> None:
        self.link_line[name] = len(self.parts)
        self.parts.append(f'  <link name="{name}"/>')

    def _joint(self, name: str, kind: str, parent: str, child: str, origin: pin.SE3, axis=None) -> None:
        rpy = pin.rpy.matrixToRpy(origin.rotation)
        lines = [f'  <joint name="{name}" type="{kind}">', f'    <parent link="{parent}"/>', f'    <child link="{child}"/>',
                 f'    <origin xyz="{_fmt(origin.translation)}" rpy="{_fmt(rpy)}"/>']
        if axis is not None:
            lines += [f'    <axis xyz="{_fmt(axis)}"/>', '    <limit effort="1e6" lower="-1e3" upper="1e3" velocity="1e3"/>']
        self.parts += lines + ["  </joint>"]

    def _body(self, b: int) -> None:
        mm = self.mm
        parent = int(mm.body_parentid[b])
        name = self.body_name(b)
        M = self.offset[parent] * (self.world[parent].actInv(self.world[b]))  # parent link -> body at qpos0
        prev = self.body_name(parent)
        first, count = int(mm.body_jntadr[b]), int(mm.body_jntnum[b])
        if count == 0:
            self._link(name)
            self._joint(f"{name}_fixed", "fixed", prev, name, M)
            M = pin.SE3.Identity()
        for k, j in enumerate(range(first, first + count)):
            jname, kind = self.joint_name(j), int(mm.jnt_type[j])
            axis, pos = mm.jnt_axis[j].astype(float), mm.jnt_pos[j].astype(float)
            ref = float(mm.qpos0[mm.jnt_qposadr[j]])
            child = name if k == count - 1 else f"{name}__{jname}"
            self._link(child)
            if kind == HINGE:
                origin = M * pin.SE3(np.eye(3), pos) * pin.SE3(pin.exp3(-ref * axis), np.zeros(3))
                self._joint(jname, "revolute", prev, child, origin, axis)
                M = pin.SE3(np.eye(3), -pos)
            elif kind == SLIDE:
                self._joint(jname, "prismatic", prev, child, M * pin.SE3(np.eye(3), -ref * axis), axis)
                M = pin.SE3.Identity()
            else:
                raise MalformedDescription(f"MJCF joint {jname!r}", "ball and free joints have no URDF tree counterpart: "
                                           "write a ball joint as three hinges, fix or drop a free joint")
            prev = child
        self.offset[b] = M
        self._inertial(b, name)
        for s in range(mm.nsite):
            if int(mm.site_bodyid[s]) == b:
                self._frame(self._name(self.obj.mjOBJ_SITE, s, "site"), b, _se3(mm.site_quat[s], mm.site_pos[s]))

    def _inertial(self, b: int, name: str) -> None:
        mm = self.mm
        mass = float(mm.body_mass[b])
        if mass <= 0:
            return
        X = self.offset[b] * _se3(mm.body_iquat[b], mm.body_ipos[b])
        ixx, iyy, izz = (float(x) for x in mm.body_inertia[b])
        self.parts[self.link_line[name]] = "\n".join([
            f'  <link name="{name}">', "    <inertial>",
            f'      <origin xyz="{_fmt(X.translation)}" rpy="{_fmt(pin.rpy.matrixToRpy(X.rotation))}"/>',
            f'      <mass value="{mass!r}"/>',
            f'      <inertia ixx="{ixx!r}" iyy="{iyy!r}" izz="{izz!r}" ixy="0" ixz="0" iyz="0"/>',
            "    </inertial>", "  </link>"])

    def _frame(self, frame: str, b: int, placement: pin.SE3) -> None:
        """A fixed link `frame` at `placement` in body b's frame."""
        self._link(frame)
        self._joint(f"{frame}_fixed", "fixed", self.body_name(b), frame, self.offset[b] * placement)

    def _equalities(self) -> None:
        mm = self.mm
        connects: dict[tuple[int, int], list[tuple[str, np.ndarray]]] = {}
        for e in range(mm.neq):
            if not mm.eq_active0[e]:
                continue
            name = self._name(self.obj.mjOBJ_EQUALITY, e, "equality")
            kind, o1, o2 = int(mm.eq_type[e]), int(mm.eq_obj1id[e]), int(mm.eq_obj2id[e])
            anchor = mm.eq_data[e][:3].astype(float)
            if int(mm.eq_objtype[e]) == SITE:
                o1, o2, anchor = int(mm.site_bodyid[o1]), int(mm.site_bodyid[o2]), mm.site_pos[o1].astype(float)
            if kind == CONNECT:
                connects.setdefault((o1, o2), []).append((name, anchor))
            elif kind == WELD:
                self._cut(name, "weld", o1, o2, self.world[o1].actInv(self.world[o2]))
            else:
                raise MalformedDescription(f"MJCF equality {name!r}", "only connect and weld equalities close loops")
        for (b1, b2), anchors in connects.items():
            while anchors:
                name, p = anchors.pop(0)
                other = next((a for a in anchors if np.linalg.norm(a[1] - p) > 1e-9), None)
                if other is None:
                    self._cut(name, "spherical", b1, b2, pin.SE3(np.eye(3), p))
                    continue
                anchors.remove(other)
                axis = (other[1] - p) / np.linalg.norm(other[1] - p)
                self._cut(name, "revolute", b1, b2, pin.SE3(np.eye(3), p), axis)

    def _cut(self, name: str, kind: str, b1: int, b2: int, at: pin.SE3, axis=None) -> None:
        """A cut between bodies b1 and b2, its frames at `at` (in b1's frame), coincident at qpos0."""
        if b1 == b2:
            raise MalformedDescription(f"MJCF equality {name!r}", "both sides are on one body")
        self._frame(f"{name}_a", b1, at)
        self._frame(f"{name}_b", b2, self.world[b2].actInv(self.world[b1] * at))
        extra = f' axis="{_fmt(axis)}"' if axis is not None else ""
        self.parts.append(f'  <mechkit:loop name="{name}" type="{kind}" frame_a="{name}_a" frame_b="{name}_b"{extra}/>')

    def actuated(self) -> tuple[str, ...]:
        out = []
        for u in range(self.mm.nu):
            if int(self.mm.actuator_trntype[u]) != TRN_JOINT:
                name = self._name(self.obj.mjOBJ_ACTUATOR, u, "actuator")
                raise MalformedDescription(f"MJCF actuator {name!r}", "acts on a tendon or site: only joint actuators map to joints")
            out.append(self.joint_name(int(self.mm.actuator_trnid[u][0])))
        return tuple(out)
