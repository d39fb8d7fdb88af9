"""Drake's `<drake:joint name type>` in a URDF: the tree joints Drake's URDF parser adds to URDF's own
(drake/multibody/parsing/detail_urdf_parser.cc, `UrdfParser::ParseJoint`), read as Pinocchio joints.
`<parent link>`, `<child link>` and `<origin>` are a URDF joint's; the joint frame is the child link's.

- `ball`: Drake's BallRpyJoint -> `JointModelSpherical` (the same motion; a quaternion here where
  Drake's coordinates are roll, pitch, yaw).
- `universal`: Drake's UniversalJoint, a rotation about the joint frame's x then about the rotated y
  (Drake ignores `<axis>`, and so does mechkit) -> `JointModelUniversal(x, y)`.
- `screw`: Drake's ScrewJoint about `<axis>` (default x, as URDF's), `<drake:screw_thread_pitch value>`
  m per turn (required) -> `JointModelHelicalUnaligned(axis, pitch / 2 pi)` (m per rad).
- `planar` (Drake reads it spelled `<drake:joint>` or `<joint>`): Drake's PlanarJoint, translation in and
  rotation about the plane through the child frame's origin normal to `<axis>` (default x). Drake's
  frame M has z along the axis, R_BM the smallest rotation taking z to it
  (`RotationMatrix::MakeClosestRotationToIdentityFromUnitZ`, x kept for -z) -> `JointModelPlanar` on M
  (Pinocchio's own URDF parser takes every planar joint's normal as z, whatever the axis).

Any other type (`curvilinear`; a standard type spelled as `drake:joint`, which Drake refuses) is refused
by name. Before Pinocchio parses the URDF, each such joint becomes a `floating` joint of its name (a
free-flyer, to Pinocchio), through a massless link `<joint>_M` when M is not the child's frame; the built
tree then gets the Pinocchio joint in its place (`mechkit.sources.rebuilt_tree.rebuild`).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.closure_elements import DRAKE
from mechkit.sources.drake_elements import _numbers, _transform
from mechkit.sources.rebuilt_tree import rebuild

#: The `drake:joint` types read (see the module docstring).
TYPES = ("ball", "universal", "screw", "planar")


def placeholders(root: ET.Element) -> dict[str, pin.JointModel]:
    """Put a `floating` joint in place of each `drake:joint` and planar joint of a URDF (see the module).

    Args:
        root: the URDF's `<robot>` element, changed in place.

    Returns:
        Joint name -> the Pinocchio joint it is (`with_joints` puts it in the built tree).

    Raises:
        MalformedDescription: a type mechkit does not read, a missing or malformed axis or pitch.
    """
    out = {}
    for k, element in enumerate(list(root)):
        custom = element.tag == f"{{{DRAKE}}}joint"
        if not custom and not (element.tag == "joint" and element.get("type") == "planar"):
            continue
        name, kind = element.get("name", ""), element.get("type", "")
        where = f"{'drake:' if custom else ''}joint {name!r}"
        if kind not in TYPES:
            raise MalformedDescription(where, f"type {kind!r}: mechkit reads drake:joint of types {TYPES}")
        axis = _axis(element, where)
        pitch = element.find(f"{{{DRAKE}}}screw_thread_pitch")
        if kind == "screw" and pitch is None:
            raise MalformedDescription(where, "a screw joint needs <drake:screw_thread_pitch value='m per turn'/>")
        pitch = _numbers(pitch.get("value", ""), 1, f"{where} drake:screw_thread_pitch")[0] if kind == "screw" else 0
        out[name] = _joint(kind, axis, pitch)
        joint = ET.Element("joint", name=name, type="floating")
        for tag in ("parent", "child", "origin"):
            if element.find(tag) is not None:
                joint.append(element.find(tag))
        root.remove(element)
        root.insert(k, joint)
        if kind == "planar" and not np.array_equal(axis, [0.0, 0.0, 1.0]):
            _through_m(root, joint, _closest_from_z(axis))
    return out


def _joint(kind: str, axis: np.ndarray, pitch: float) -> pin.JointModel:
    if kind == "universal":
        return pin.JointModelUniversal(np.eye(3)[0], np.eye(3)[1])
    if kind == "screw":
        return pin.JointModelHelicalUnaligned(axis, pitch / (2 * np.pi))
    return pin.JointModelSpherical() if kind == "ball" else pin.JointModelPlanar()


def with_joints(model: pin.Model, joints: dict[str, pin.JointModel]) -> pin.Model:
    """The tree built from `placeholders`' URDF with its joints put in.

    Args:
        model: Pinocchio's model of that URDF.
        joints: what `placeholders` returned.

    Returns:
        The model with each placeholder free-flyer replaced (same placement, body, frames).
    """
    return rebuild(model, {model.getJointId(name): joint for name, joint in joints.items()}, {}, [])


def _axis(element: ET.Element, where: str) -> np.ndarray:
    """The unit `<axis xyz>` (URDF's and Drake's default x)."""
    node = element.find("axis")
    axis = _numbers(node.get("xyz", "1 0 0") if node is not None else "1 0 0", 3, f"{where} axis")
    if np.linalg.norm(axis) < 1e-8:
        raise MalformedDescription(where, "its axis is zero")
    return axis / np.linalg.norm(axis)


def _closest_from_z(axis: np.ndarray) -> np.ndarray:
    """Drake's MakeClosestRotationToIdentityFromUnitZ: the rotation of least angle taking z to `axis`
    (about x for -z)."""
    cross = np.cross([0.0, 0.0, 1.0], axis)
    norm = np.linalg.norm(cross)
    about = np.array([1.0, 0.0, 0.0]) if norm < 1e-10 else cross / norm
    return pin.exp3(about * np.arctan2(norm, axis[2]))


def _through_m(root: ET.Element, joint: ET.Element, r_bm: np.ndarray) -> None:
    """Make `joint` end on a massless link `<joint>_M` at frame M (X_BM = (r_bm, 0)) and fix the child B
    to it at X_MB."""
    origin = joint.find("origin")
    xyz, rpy = (_numbers(origin.get(a, "0 0 0") if origin is not None else "0 0 0", 3, a) for a in ("xyz", "rpy"))
    x_bm = np.eye(4)
    x_bm[:3, :3] = r_bm
    child, link = joint.find("child").get("link"), f"{joint.get('name')}_M"
    joint.find("child").set("link", link)
    if origin is not None:
        joint.remove(origin)
    root.append(ET.Element("link", name=link))
    fixed = ET.SubElement(root, "joint", name=f"{link}_fixed", type="fixed")
    ET.SubElement(fixed, "parent", link=link)
    ET.SubElement(fixed, "child", link=child)
    for node, place in ((joint, _transform(xyz, rpy) @ x_bm), (fixed, np.linalg.inv(x_bm))):
        rpy_out = pin.rpy.matrixToRpy(place[:3, :3])
        ET.SubElement(
            node,
            "origin",
            xyz=" ".join(repr(float(v)) for v in place[:3, 3]),
            rpy=" ".join(repr(float(v)) for v in rpy_out),
        )
