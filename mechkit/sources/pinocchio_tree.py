"""Building a Pinocchio tree directly (for readers whose format is not URDF: MJCF, SDFormat), and its
URDF text where URDF can hold it.

Frames follow Pinocchio's URDF parser: a JOINT frame per joint, a BODY frame per body (on the joint
that carries it), an OP_FRAME per other named frame (MJCF sites, SDFormat frames, cut frames), so a
reader's model and the model Pinocchio builds from `tree_urdf` have the same named frames.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription
from mechkit.core import LoopClosure
from mechkit.sources.urdf import LOOP_NAMESPACE

#: Pinocchio's one-freedom joints along a coordinate axis: short name -> (URDF type, unit axis).
_ALIGNED = {
    f"JointModel{k}{a}": (kind, np.eye(3)[i])
    for k, kind in (("R", "revolute"), ("P", "prismatic"))
    for i, a in enumerate("XYZ")
}
_UNALIGNED = {"JointModelRevoluteUnaligned": "revolute", "JointModelPrismaticUnaligned": "prismatic"}


def joint_model(kind: str, axis: np.ndarray | None = None, axis2: np.ndarray | None = None) -> pin.JointModel:
    """The Pinocchio joint of a kind: a coordinate-aligned one where the unit axis is +x, +y or +z
    (as Pinocchio's URDF parser chooses), else the unaligned one.

    Args:
        kind: "revolute", "prismatic", "spherical", "universal" or "free".
        axis: unit axis in the joint frame (revolute, prismatic, the first of a universal joint).
        axis2: a universal joint's second axis, in the joint frame.

    Returns:
        The joint model.
    """
    if kind in ("revolute", "prismatic"):
        for name, (k, unit) in _ALIGNED.items():
            if k == kind and np.array_equal(axis, unit):
                return getattr(pin, name)()
        return pin.JointModelRevoluteUnaligned(axis) if kind == "revolute" else pin.JointModelPrismaticUnaligned(axis)
    if kind == "universal":
        return pin.JointModelUniversal(axis, axis2)
    return pin.JointModelSpherical() if kind == "spherical" else pin.JointModelFreeFlyer()


def add_joint(model: pin.Model, name: str, parent: int, joint: pin.JointModel, placement: pin.SE3) -> int:
    """Add a joint and its JOINT frame.

    Args:
        model: the model, extended in place.
        name: the joint's name.
        parent: the parent joint's id.
        joint: the joint model.
        placement: the joint frame at zero coordinates, in the parent joint's frame.

    Returns:
        The joint's id.

    Raises:
        MalformedDescription: a second joint of that name.
    """
    if model.existJointName(name):
        raise MalformedDescription(f"joint {name!r}", "a second joint of that name")
    jid = model.addJoint(parent, joint, placement, name)
    model.addJointFrame(jid, _parent_frame(model, parent))
    return jid


def add_body(model: pin.Model, name: str, joint: int, placement: pin.SE3, inertia: pin.Inertia) -> None:
    """Add a body (its inertia to the joint, a BODY frame).

    Args:
        model: the model, extended in place.
        name: the body's name.
        joint: the joint carrying it.
        placement: the body frame in the joint's frame.
        inertia: its inertia (kg, m, kg m^2), in the body frame.

    Raises:
        MalformedDescription: the name is taken by a body or frame.
    """
    model.appendBodyToJoint(joint, inertia, placement)
    _add(model, pin.Frame(name, joint, _parent_frame(model, joint), placement, pin.FrameType.BODY))


def add_frame(
    model: pin.Model, name: str, joint: int, placement: pin.SE3, kind: pin.FrameType = pin.FrameType.OP_FRAME
) -> None:
    """Add a frame (operational, or a fixed joint's).

    Args:
        model: the model, extended in place.
        name: the frame's name.
        joint: the joint carrying it.
        placement: the frame in the joint's frame.
        kind: its Pinocchio frame type.

    Raises:
        MalformedDescription: the name is taken by a body or frame.
    """
    _add(model, pin.Frame(name, joint, _parent_frame(model, joint), placement, kind))


def _add(model: pin.Model, frame: pin.Frame) -> None:
    """Add a body or operational frame; its name may be a joint's, not another body's or frame's."""
    if any(f.name == frame.name and f.type != pin.FrameType.JOINT for f in model.frames):
        raise MalformedDescription(f"frame {frame.name!r}", "a second body or frame of that name")
    model.addFrame(frame, False)


def _parent_frame(model: pin.Model, joint: int) -> int:
    """The frame a joint's children hang from: its JOINT frame (the universe's first frame for 0)."""
    for i, frame in enumerate(model.frames):
        if frame.parentJoint == joint and frame.type == pin.FrameType.JOINT:
            return i
    return 0


def one_freedom_axes(model: pin.Model) -> dict[int, tuple[str, np.ndarray | None]] | None:
    """Joint id -> (URDF type, unit axis in the joint frame) for every joint, or None when some joint
    is neither a one-freedom revolute or prismatic joint nor a free-flyer on the world (URDF's
    "floating", which Pinocchio's parser reads as a free-flyer): URDF cannot hold it.

    Args:
        model: the model.

    Returns:
        Joint id -> ("revolute" or "prismatic", unit axis (3,) in the joint frame; or ("floating", None)),
        or None.
    """
    out: dict[int, tuple[str, np.ndarray | None]] = {}
    for j in range(1, model.njoints):
        short = model.joints[j].shortname()
        if short in _ALIGNED:
            out[j] = _ALIGNED[short]
        elif short in _UNALIGNED:
            out[j] = (_UNALIGNED[short], np.asarray(model.joints[j].extract().axis, dtype=float))
        elif short == "JointModelFreeFlyer" and model.parents[j] == 0:
            out[j] = ("floating", None)
        else:
            return None
    return out


def tree_urdf(model: pin.Model, closures: tuple[LoopClosure, ...]) -> str | None:
    """URDF text of a tree of revolute and prismatic joints (and a floating root) with its `<mechkit:loop>`s, or
    None when URDF cannot hold the tree (ball, universal joints, a free-flyer below the root).

    Each joint's link is named after the BODY frame at identity on it (else `<joint>__link`) and
    carries the joint's whole inertia; every other frame but the universe and JOINT frames is a
    massless link on a fixed joint `<frame>_fixed`. Joint limits are written wide (+-1e3), efforts and speeds 1e6 / 1e3.

    Args:
        model: the tree.
        closures: its loop closures (written as `<mechkit:loop>`s).

    Returns:
        The URDF text, or None.
    """
    axes = one_freedom_axes(model)
    if axes is None:
        return None
    frames = [f for f in list(model.frames)[1:] if f.type != pin.FrameType.JOINT]
    link = {0: "world"}
    for j in range(1, model.njoints):
        link[j] = next(
            (
                f.name
                for f in frames
                if f.parentJoint == j and f.type == pin.FrameType.BODY and f.placement.isIdentity()
            ),
            f"{model.names[j]}__link",
        )
    lines = [f'<robot name="{model.name or "tree"}" xmlns:mechkit="{LOOP_NAMESPACE}">']
    for j in range(model.njoints):
        lines += _link(link[j], model.inertias[j] if j else None)
        if j:
            kind, axis = axes[j]
            lines += _joint(model.names[j], kind, link[model.parents[j]], link[j], model.jointPlacements[j], axis)
    for frame in frames:
        if frame.name != link[frame.parentJoint]:
            lines += _link(frame.name, None)
            lines += _joint(f"{frame.name}_fixed", "fixed", link[frame.parentJoint], frame.name, frame.placement)
    lines += [_loop(c) for c in closures]
    return "\n".join(lines + ["</robot>"]) + "\n"


def _numbers(values) -> str:
    return " ".join(repr(float(x)) for x in np.ravel(values))


def _link(name: str, inertia: pin.Inertia | None) -> list[str]:
    if inertia is None or (inertia.mass <= 0 and not np.any(inertia.inertia)):
        return [f'  <link name="{name}"/>']
    i = [[float(x) for x in row] for row in inertia.inertia]
    tensor = " ".join(
        f'{k}="{i[r][c]!r}"'
        for k, r, c in (("ixx", 0, 0), ("iyy", 1, 1), ("izz", 2, 2), ("ixy", 0, 1), ("ixz", 0, 2), ("iyz", 1, 2))
    )
    return [
        f'  <link name="{name}">',
        "    <inertial>",
        f'      <origin xyz="{_numbers(inertia.lever)}" rpy="0 0 0"/>',
        f'      <mass value="{float(inertia.mass)!r}"/>',
        f"      <inertia {tensor}/>",
        "    </inertial>",
        "  </link>",
    ]


def _joint(name: str, kind: str, parent: str, child: str, origin: pin.SE3, axis=None) -> list[str]:
    lines = [
        f'  <joint name="{name}" type="{kind}">',
        f'    <parent link="{parent}"/>',
        f'    <child link="{child}"/>',
        f'    <origin xyz="{_numbers(origin.translation)}" rpy="{_numbers(pin.rpy.matrixToRpy(origin.rotation))}"/>',
    ]
    if axis is not None:
        lines += [
            f'    <axis xyz="{_numbers(axis)}"/>',
            '    <limit effort="1e6" lower="-1e3" upper="1e3" velocity="1e3"/>',
        ]
    return lines + ["  </joint>"]


def _loop(c: LoopClosure) -> str:
    extra = "".join(
        f' {attr}="{_numbers(value)}"'
        for attr, value in (("axis", c.axis), ("axis_a", c.axis_a), ("axis_b", c.axis_b))
        if value is not None
    )
    return f'  <mechkit:loop name="{c.name}" type="{c.kind}" frame_a="{c.frame_a}" frame_b="{c.frame_b}"{extra}/>'
