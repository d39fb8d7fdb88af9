"""Export a mechanism for other tools: MJCF (MuJoCo) and Extended URDF (Gepetto's sidecar convention).

MJCF: one `<body>` per Pinocchio joint (its frame is the joint frame), `<inertial>` from the
model, every URDF frame as a `<site>`, the actuated joints as `<motor>`s (ctrl = joint effort, N m
or N), and each loop closure as MuJoCo `<equality>` elements:

| cut kind / rows | MJCF |
|---|---|
| revolute, rows planar | one `connect` at the pin (3 rows; the out-of-plane one is redundant) |
| revolute, rows spatial or spherical | two `connect`s on the axis, `AXIS_ANCHOR_OFFSET` apart |
| spherical | one `connect` |
| weld | one `weld` |
| hooke, prismatic | none exists: `MethodUnavailable` |

MuJoCo's `connect` (and Pinocchio's MJCF reader) take the second body's anchor from the
configuration in which the model is written, so the bodies are written at the assembled home
configuration, each joint with `ref` = its home value: MuJoCo's qpos then equals Pinocchio's q
(same joint order, same zero). Contacts are off (no geoms); gravity -9.81 m/s^2 along world z.

Extended URDF (Batto, de Matteis, Mansard; Gepetto's example-parallel-robots): the tree URDF plus a
YAML sidecar `closed_loop: [[frame_a, frame_b], ...]`, `type: ['3d' | '6d', ...]`, `name_mot`,
`joint_name`, `joint_type`. A 3d pair is a point anchor, 6d a weld. A revolute cut with spatial
rows becomes two 3d pairs; the second pair's frames (`<frame>_axis`) are added to the URDF on
fixed joints, `AXIS_ANCHOR_OFFSET` along the axis.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin

from mechkit.closures import AXIS_ANCHOR_OFFSET
from mechkit.exceptions import InvalidParameters, MethodUnavailable
from mechkit.structure import body_name

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

FORMATS = ("mjcf", "extended-urdf")
#: Name of the fixed MJCF body that carries the ground side of the mechanism.
ROOT_BODY = "ground"


def _fmt(values) -> str:
    return " ".join(repr(float(x)) for x in np.ravel(values))


def _quat_wxyz(rotation: np.ndarray) -> np.ndarray:
    x, y, z, w = pin.Quaternion(rotation).coeffs()
    return np.array([w, x, y, z])


def _joint_kind(model: pin.Model, joint: int) -> tuple[str, np.ndarray]:
    """MJCF joint type and axis (joint frame) of a one-coordinate Pinocchio joint."""
    jm = model.joints[joint]
    short = jm.shortname()
    if model.nqs[joint] != 1 or model.nvs[joint] != 1:
        raise MethodUnavailable("mjcf export", f"joint {model.names[joint]!r} ({short}) has {model.nqs[joint]} coordinates; "
                                "only one-coordinate revolute and prismatic joints are exported")
    for kind, prefix in (("hinge", "JointModelR"), ("slide", "JointModelP")):
        if short.startswith(prefix):
            if short[len(prefix):] in ("X", "Y", "Z"):
                return kind, np.eye(3)["XYZ".index(short[-1])]
            return kind, np.asarray(jm.extract().axis, dtype=float)
    raise MethodUnavailable("mjcf export", f"joint {model.names[joint]!r} is {short}")


def _equalities(mech: Mechanism, names: dict[int, str]) -> list[tuple[str, dict[str, str]]]:
    """MJCF equality elements (tag, attributes) of the closures."""
    model = mech.model
    out = []
    for cut in mech.cuts:
        c = cut.closure
        fa, fb = model.frames[cut.frame_a], model.frames[cut.frame_b]
        body1, body2 = names[fa.parentJoint], names[fb.parentJoint]
        if c.kind == "weld":
            out.append(("weld", {"name": c.name, "body1": body1, "body2": body2}))
            continue
        if c.kind in ("hooke", "prismatic"):
            raise MethodUnavailable("mjcf export", f"cut {c.name!r} is {c.kind}: MuJoCo has no equality constraint for it")
        offsets = [np.zeros(3)]
        if c.kind == "revolute" and c.rows != "planar":
            offsets.append(AXIS_ANCHOR_OFFSET * c.axis)
        for k, offset in enumerate(offsets):
            anchor = fa.placement.act(offset)
            out.append(("connect", {"name": f"{c.name}" + (f"_{k}" if k else ""), "body1": body1,
                                    "body2": body2, "anchor": _fmt(anchor)}))
    return out


def to_mjcf(mech: Mechanism, q: np.ndarray | None = None) -> str:
    """MJCF text of the mechanism, bodies written at q (default: the home assembly).

    Raises:
        MethodUnavailable: a joint or cut with no MJCF counterpart.
    """
    model = mech.model
    q = mech.home_q if q is None else np.asarray(q, dtype=float)
    root = ET.Element("mujoco", model=mech.spec.name)
    ET.SubElement(root, "compiler", angle="radian", autolimits="true")
    ET.SubElement(root, "option", gravity=_fmt(model.gravity.linear), timestep="0.001")
    # one jointless root body holds every tree: Pinocchio's MJCF reader takes the first body only
    world = ET.SubElement(ET.SubElement(root, "worldbody"), "body", name=ROOT_BODY)
    names = {0: ROOT_BODY}
    elements = {0: world}
    for j in range(1, model.njoints):
        kind, axis = _joint_kind(model, j)
        value = q[model.idx_qs[j]]
        motion = axis * value
        M = model.jointPlacements[j] * (pin.exp6(pin.Motion(np.zeros(3), motion)) if kind == "hinge"
                                        else pin.SE3(np.eye(3), motion))
        names[j] = body_name(model, j)
        body = ET.SubElement(elements[model.parents[j]], "body", name=names[j], pos=_fmt(M.translation),
                             quat=_fmt(_quat_wxyz(M.rotation)))
        inertia = model.inertias[j]
        if inertia.mass > 0:
            I = inertia.inertia
            full = [I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2], I[1, 2]]
            ET.SubElement(body, "inertial", pos=_fmt(inertia.lever), mass=repr(float(inertia.mass)), fullinertia=_fmt(full))
        ET.SubElement(body, "joint", name=model.names[j], type=kind, axis=_fmt(axis), ref=repr(float(value)))
        elements[j] = body
    for frame in model.frames:
        if frame.type == pin.FrameType.BODY and not frame.placement.isIdentity():
            ET.SubElement(elements[frame.parentJoint], "site", name=frame.name, pos=_fmt(frame.placement.translation),
                          quat=_fmt(_quat_wxyz(frame.placement.rotation)))
    equality = ET.SubElement(root, "equality")
    for tag, attrs in _equalities(mech, names):
        ET.SubElement(equality, tag, attrs)
    actuator = ET.SubElement(root, "actuator")
    for joint in mech.actuated:
        ET.SubElement(actuator, "motor", name=joint, joint=joint)
    ET.indent(root)
    return ET.tostring(root, encoding="unicode") + "\n"


def to_extended_urdf(mech: Mechanism) -> tuple[str, str]:
    """(URDF text, YAML sidecar text) in the Extended URDF convention.

    Raises:
        MethodUnavailable: a hooke or prismatic cut (no 3d/6d equivalent).
    """
    robot = ET.fromstring(mech.urdf)
    pairs: list[tuple[str, str]] = []
    kinds: list[str] = []
    frame_parent = {j.find("child").get("link"): j for j in robot.findall("joint")}
    for cut in mech.cuts:
        c = cut.closure
        if c.kind in ("hooke", "prismatic"):
            raise MethodUnavailable("extended-urdf export", f"cut {c.name!r} is {c.kind}: the sidecar has only 3d and 6d pairs")
        pairs.append((c.frame_a, c.frame_b))
        kinds.append("6d" if c.kind == "weld" else "3d")
        if c.kind == "revolute" and c.rows != "planar":
            extra = []
            for frame in (c.frame_a, c.frame_b):
                if frame not in frame_parent:
                    raise MethodUnavailable("extended-urdf export", f"frame {frame!r} is not a URDF link on a joint")
                # the closure axis is given in frame_a's frame, and both frames share orientation when closed
                name = f"{frame}_axis"
                ET.SubElement(robot, "link", name=name)
                j = ET.SubElement(robot, "joint", name=f"{name}_fixed", type="fixed")
                ET.SubElement(j, "parent", link=frame)
                ET.SubElement(j, "child", link=name)
                axis_in_frame = c.axis if frame == c.frame_a else frame_b_vector(mech, cut, c.axis)
                ET.SubElement(j, "origin", xyz=_fmt(AXIS_ANCHOR_OFFSET * axis_in_frame), rpy="0 0 0")
                extra.append(name)
            pairs.append((extra[0], extra[1]))
            kinds.append("3d")
    for loop in [el for el in robot if el.tag.endswith("}loop") or el.tag == "loop"]:
        robot.remove(loop)
    ET.indent(robot)
    urdf = '<?xml version="1.0" ?>\n' + ET.tostring(robot, encoding="unicode") + "\n"
    yaml = (f"closed_loop: {[list(p) for p in pairs]}\n"
            f"type: {kinds}\n"
            f"name_mot: {list(mech.actuated)}\n"
            "joint_name: []\njoint_type: []\n")
    return urdf, yaml


def frame_b_vector(mech: Mechanism, cut, vector: np.ndarray) -> np.ndarray:
    """A vector given in a cut's frame_a, expressed in its frame_b at the home assembly (loop closed)."""
    pin.framesForwardKinematics(mech.model, mech.data, mech.home_q)
    Ra = mech.data.oMf[cut.frame_a].rotation
    Rb = mech.data.oMf[cut.frame_b].rotation
    return Rb.T @ Ra @ np.asarray(vector, dtype=float)


def export_command(mechanism: Mechanism, fmt: str, output: str | Path) -> list[Path]:
    """Write the mechanism in `fmt` ("mjcf" or "extended-urdf") to `output`; returns the files written.

    extended-urdf also writes the YAML sidecar beside the URDF (same stem, `.yaml`).
    """
    from mechkit.atomic import write_text

    output = Path(output)
    if fmt == "mjcf":
        write_text(output, to_mjcf(mechanism))
        return [output]
    if fmt == "extended-urdf":
        urdf, yaml = to_extended_urdf(mechanism)
        sidecar = output.with_suffix(".yaml")
        write_text(output, urdf)
        write_text(sidecar, yaml)
        return [output, sidecar]
    raise InvalidParameters("format", fmt, f"expected one of {FORMATS}")
