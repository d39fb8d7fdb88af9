"""An SDFormat file (`.sdf`), read with an XML parser (the PyPI build of Pinocchio has no SDF parser)
into a Pinocchio model with closure records.

The file holds one `<model>` of links and joints (nested models, `<include>` and world files are
refused by name). Its joints may form a graph; it becomes a spanning tree plus cut joints:

- the tree joint of a link is, among the joints whose child it is, the one named in
  `parent_guidance`, else the first in file order (Pinocchio's SDF parser chooses so); its other
  parent joints are cuts. A link no joint leads to is a root: a free-flyer (`root_joint`, or
  `<link>_root_joint` when there are several). A `<static>` model (nothing moves) is refused.
- a cut joint is a `LoopClosure` between frames `<joint>_a` on its parent link and `<joint>_b` on its
  child link, both at the joint's frame in the file's configuration: revolute / continuous ->
  revolute, prismatic -> prismatic, ball -> spherical, fixed -> weld, universal -> Hooke.
- `gearbox` joints are couplings, not tree edges: theta_2 = -gearbox_ratio theta_1, theta_1 the
  angle of the parent link from `gearbox_reference_body` about `axis`, theta_2 the child link's about
  `axis2`, each the coordinate of the revolute tree joint between that link and the reference body
  (its sign flipped when the joint runs the other way or its axis is opposite). Their inputs
  (theta_1's joints) are the actuated joints: SDFormat names no motor, a gearbox is one's output.

Poses: SDFormat before 1.7 places links in the model frame and joints in their child link's frame,
`<use_parent_model_frame>` puts an axis in the model frame (the 1.5/1.6 `frame` attribute of `<pose>`
is refused); from 1.7, `relative_to` names any link, joint, `<frame>` or `__model__` (links default
to the model frame, joints to their child, frames to `attached_to`), an axis's `expressed_in` too,
`degrees` and `rotation_format` are read. A joint's coordinate is 0 in the file's configuration.
Tree joints: revolute and continuous (one coordinate, an angle), prismatic, ball, universal, fixed
(the child's inertia joins the parent's joint). Inertia: `<inertial>` in the link frame, SDFormat's
defaults where absent (1 kg, unit inertia). Springs: `<dynamics>` `spring_stiffness`,
`spring_reference`, `damping` of tree joints; a cut joint's damping is not read (no coordinate
carries it), its stiffness is refused. Limits, friction, plugins and geometry are not read.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription
from mechkit.core import Coupling, JointSpring, LoopClosure
from mechkit.sources.description import Description, read_text
from mechkit.sources.pinocchio_tree import add_body, add_frame, add_joint, joint_model, tree_urdf
from mechkit.sources.urdf import parse_xml

#: SDFormat joint type -> Pinocchio joint kind (tree) and cut kind.
KINDS = {"revolute": ("revolute", "revolute"), "continuous": ("revolute", "revolute"),
         "prismatic": ("prismatic", "prismatic"), "ball": ("spherical", "spherical"),
         "universal": ("universal", "hooke"), "fixed": (None, "weld"), "gearbox": (None, None)}
MODEL = "__model__"


def read_sdf(path: Path, parent_guidance: Sequence[str] = ()) -> Description:
    """The description in an SDFormat file (see the module docstring).

    Args:
        path: the `.sdf` file.
        parent_guidance: joint names to prefer as tree joints of links with several parent joints.

    Returns:
        `Description` with `model` (and `urdf` for a tree of revolute and prismatic joints),
        closures, couplings (gearboxes), springs, actuated (gearbox inputs), home and guess (the
        file's configuration: zero coordinates, a free root at its pose in the world).

    Raises:
        MalformedDescription: not SDFormat, or any element mechkit cannot place or read, named.
    """
    root = parse_xml(read_text(path), str(path))
    if root.tag != "sdf":
        raise MalformedDescription(str(path), f"root element <{root.tag}>: an SDFormat file starts with <sdf>")
    models = root.findall("model")
    if root.find("world") is not None or len(models) != 1:
        raise MalformedDescription(str(path), f"expected one <model> under <sdf>, found {len(models)}"
                                   + (" and a <world>" if root.find("world") is not None else ""))
    return _Reader(models[0], _version(root, str(path)), tuple(parent_guidance)).description(path)


def _version(root: ET.Element, where: str) -> tuple[int, int]:
    text = root.get("version", "")
    try:
        major, minor = (int(x) for x in text.split("."))
    except ValueError:
        raise MalformedDescription(where, f"<sdf version={text!r}>: expected a version such as 1.6") from None
    return major, minor


def _numbers(element: ET.Element | None, where: str, count: int, default: tuple[float, ...]) -> np.ndarray:
    if element is None or not (element.text or "").strip():
        return np.array(default, dtype=float)
    try:
        values = np.array([float(x) for x in element.text.split()])
    except ValueError:
        raise MalformedDescription(where, f"<{element.tag}> {element.text.strip()!r} is not {count} numbers") from None
    if values.shape != (count,) or not np.all(np.isfinite(values)):
        raise MalformedDescription(where, f"<{element.tag}> {element.text.strip()!r} is not {count} finite numbers")
    return values


def _number(element: ET.Element, tag: str, where: str, default: float | None) -> float:
    child = element.find(tag)
    if child is None and default is None:
        raise MalformedDescription(where, f"missing <{tag}>")
    return float(default if child is None else _numbers(child, where, 1, (default or 0.0,))[0])


class _Reader:
    """One SDFormat model: its frames, tree, cuts, couplings and springs."""

    def __init__(self, model: ET.Element, version: tuple[int, int], guidance: tuple[str, ...]):
        self.element, self.version, self.guidance = model, version, guidance
        self.name = model.get("name") or "model"
        for tag in ("model", "include"):
            if model.find(tag) is not None:
                raise MalformedDescription(f"SDF model {self.name!r}", f"nested <{tag}> is not read")
        self.items: dict[str, dict[str, ET.Element]] = {"link": {}, "joint": {}, "frame": {}}
        for kind, table in self.items.items():
            for element in model.findall(kind):
                name = element.get("name")
                if not name or name in table or (version >= (1, 7) and any(name in t for t in self.items.values())):
                    raise MalformedDescription(f"SDF {kind} {name!r}", "missing or repeated name")
                table[name] = element
        if not self.items["link"]:
            raise MalformedDescription(f"SDF model {self.name!r}", "has no link")
        self.poses: dict[str, pin.SE3] = {}
        self.world = self._pose(model.find("pose"), f"SDF model {self.name!r}")[0]  # model frame in the world

    def _pose(self, element: ET.Element | None, where: str) -> tuple[pin.SE3, str | None]:
        """(placement, the frame it is relative to, None for the default) of a `<pose>`."""
        if element is None:
            return pin.SE3.Identity(), None
        if element.get("frame"):
            raise MalformedDescription(where, "the <pose frame> attribute (SDFormat 1.5/1.6) is not read: "
                                       "write SDFormat 1.7 relative_to")
        quat = element.get("rotation_format", "euler_rpy") == "quat_xyzw"
        if element.get("rotation_format", "euler_rpy") not in ("euler_rpy", "quat_xyzw"):
            raise MalformedDescription(where, f"rotation_format {element.get('rotation_format')!r} is not read")
        v = _numbers(element, where, 7 if quat else 6, (0.0,) * (7 if quat else 6))
        if quat:
            rotation = pin.Quaternion(v[6], v[3], v[4], v[5]).normalized().matrix()
        else:
            rotation = pin.rpy.rpyToMatrix(*(np.radians(v[3:]) if element.get("degrees") == "true" else v[3:]))
        return pin.SE3(rotation, v[:3]), element.get("relative_to") or None

    def frame(self, name: str, stack: tuple[str, ...] = ()) -> pin.SE3:
        """A frame's pose in the model frame, in the file's configuration (`world`: the world frame)."""
        if name == MODEL:
            return pin.SE3.Identity()
        if name == "world":
            return self.world.inverse()
        if name in self.poses:
            return self.poses[name]
        kind = next((k for k, table in self.items.items() if name in table), None)
        where = f"SDF {stack[-1] if stack else 'frame'}" if kind is None else f"SDF {kind} {name!r}"
        if kind is None:
            raise MalformedDescription(where, f"relative_to / attached_to / expressed_in {name!r}: no such frame")
        if name in stack:
            raise MalformedDescription(where, "pose cycle: " + " -> ".join((*stack[stack.index(name):], name)))
        element = self.items[kind][name]
        placement, relative = self._pose(element.find("pose"), where)
        if relative is not None and self.version < (1, 7):
            raise MalformedDescription(where, "relative_to needs SDFormat 1.7 or later")
        default = (self._end(element, "child", where) if kind == "joint" else
                   element.get("attached_to") or MODEL if kind == "frame" else MODEL)
        self.poses[name] = self.frame(relative or default, (*stack, name)) * placement
        return self.poses[name]

    def _end(self, joint: ET.Element, tag: str, where: str) -> str:
        """A joint's parent or child link (`world` allowed as a parent)."""
        return self._link_of((joint.findtext(tag) or "").strip(), f"<{tag}>", where, tag == "parent")

    def _link_of(self, name: str, what: str, where: str, world: bool = False) -> str:
        """The link a frame name stands for: a link, or what a `<frame>` is attached to, or a joint's child."""
        seen: list[str] = []
        while name in self.items["frame"] or name in self.items["joint"]:
            if name in seen:
                raise MalformedDescription(where, f"{what} {name!r}: attached_to cycle")
            seen.append(name)
            frame = self.items["frame"].get(name)
            name = (frame.get("attached_to") or MODEL) if frame is not None else (
                self.items["joint"][name].findtext("child") or "").strip()
        if name not in self.items["link"] and not (world and name == "world"):
            raise MalformedDescription(where, f"{what} {name!r} is not a link of the model")
        return name

    def axis(self, joint: ET.Element, tag: str, where: str) -> np.ndarray:
        """A joint's `axis` / `axis2` as a unit vector in the joint frame."""
        element = joint.find(tag)
        if element is None:
            raise MalformedDescription(where, f"missing <{tag}>")
        xyz = element.find("xyz")
        vector = _numbers(xyz, where, 3, (0.0, 0.0, 1.0))
        if np.linalg.norm(vector) < 1e-12:
            raise MalformedDescription(where, f"<{tag}><xyz> is zero")
        if self.version < (1, 7):
            model_frame = (element.findtext("use_parent_model_frame") or "").strip() in ("1", "true")
            frame = MODEL if model_frame else None
        else:
            frame = xyz.get("expressed_in") if xyz is not None else None
        R = self.frame(joint.get("name")).rotation
        if frame is not None:
            vector = R.T @ self.frame(frame, (joint.get("name"),)).rotation @ vector
        return vector / np.linalg.norm(vector)

    def description(self, path: Path) -> Description:
        """Build the model and the records (see the module docstring)."""
        joints = self.items["joint"]
        parents: dict[str, list[str]] = {link: [] for link in self.items["link"]}
        ends: dict[str, tuple[str, str]] = {}
        for name, joint in joints.items():
            where = f"SDF joint {name!r}"
            if joint.get("type") not in KINDS:
                raise MalformedDescription(where, f"type {joint.get('type')!r} is not read; known: {', '.join(KINDS)}")
            ends[name] = (self._end(joint, "parent", where), self._end(joint, "child", where))
            if ends[name][1] == ends[name][0]:
                raise MalformedDescription(where, "parent and child are one link")
            if joint.get("type") != "gearbox":
                parents[ends[name][1]].append(name)
        tree = {link: next((j for j in options if j in self.guidance), options[0]) for link, options in parents.items()
                if options}
        if (self.element.findtext("static") or "").strip() in ("1", "true"):
            raise MalformedDescription(f"SDF model {self.name!r}", "<static> is true: nothing in it moves")
        roots = [link for link in self.items["link"] if link not in tree]
        model = pin.Model()
        model.name = self.name
        add_body(model, "world", 0, pin.SE3.Identity(), pin.Inertia.Zero())
        carrier: dict[str, tuple[int, pin.SE3]] = {"world": (0, pin.SE3.Identity())}
        guess: dict[str, float | tuple[float, ...]] = {}
        queue = ["world", *roots]
        for root in roots:
            at = self.world * self.frame(root)
            name = "root_joint" if len(roots) == 1 else f"{root}_root_joint"
            carrier[root] = (add_joint(model, name, 0, pin.JointModelFreeFlyer(), pin.SE3.Identity()), pin.SE3.Identity())
            guess[name] = tuple(float(x) for x in at.translation) + tuple(float(x) for x in pin.log3(at.rotation))
            add_body(model, root, *carrier[root], self._inertia(root))
        springs: list[JointSpring] = []
        stack = list(reversed(queue))  # depth first: Pinocchio's algorithms take a subtree as contiguous joints
        while stack:
            link = stack.pop()
            if link != "world" and link not in roots:
                self._tree_joint(model, tree[link], ends[tree[link]], carrier, springs, guess)
            stack += reversed([c for c, j in tree.items() if ends[j][0] == link])
        lost = [link for link in self.items["link"] if link not in carrier]
        if lost:
            raise MalformedDescription(f"SDF link {lost[0]!r}", f"links {lost} reach neither the world nor a root: "
                                       "their parent joints form a cycle")
        for name, frame in self.items["frame"].items():  # frames on links (not those on the model frame)
            if frame.get("attached_to", MODEL) != MODEL:
                link = self._link_of(frame.get("attached_to"), "attached_to", f"SDF frame {name!r}")
                add_frame(model, name, carrier[link][0], self._in(carrier, link, self.frame(name)))
        closures = [self._cut(model, j, ends[j], carrier) for j, joint in joints.items()
                    if joint.get("type") != "gearbox" and tree.get(ends[j][1]) != j]
        couplings = [self._gearbox(j, ends[j], tree, ends) for j, joint in joints.items()
                     if joint.get("type") == "gearbox"]
        actuated = tuple(dict.fromkeys(k.leader[0][0] for k in couplings))
        return Description(self.name, tree_urdf(model, tuple(closures)), actuated, {j: 0.0 for j in actuated}, guess,
                           path, "sdf", closures=tuple(closures), model=model, couplings=tuple(couplings),
                           springs=tuple(springs))

    def _in(self, carrier: dict, link: str, X: pin.SE3) -> pin.SE3:
        """A placement X in the model frame, as a placement in the frame of the joint carrying `link`."""
        return carrier[link][1] * self.frame(link).actInv(X)

    def _inertia(self, link: str) -> pin.Inertia:
        inertial = self.items["link"][link].find("inertial")
        where = f"SDF link {link!r}"
        if inertial is None:
            return pin.Inertia(1.0, np.zeros(3), np.eye(3))
        placement, relative = self._pose(inertial.find("pose"), where)
        if relative not in (None, link):
            raise MalformedDescription(where, "an <inertial> pose relative to another frame is not read")
        mass = _number(inertial, "mass", where, 1.0)
        tensor = inertial.find("inertia")
        i = {k: _number(tensor, k, where, 1.0 if k[1] == k[2] else 0.0) if tensor is not None
             else (1.0 if k[1] == k[2] else 0.0) for k in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")}
        I = np.array([[i["ixx"], i["ixy"], i["ixz"]], [i["ixy"], i["iyy"], i["iyz"]], [i["ixz"], i["iyz"], i["izz"]]])
        R = placement.rotation
        return pin.Inertia(mass, placement.translation, R @ I @ R.T)

    def _tree_joint(self, model: pin.Model, name: str, ends: tuple[str, str], carrier: dict, springs: list,
                    guess: dict) -> None:
        joint, (parent, child) = self.items["joint"][name], ends
        where, kind = f"SDF joint {name!r}", KINDS[self.items["joint"][name].get("type")][0]
        at = self._in(carrier, parent, self.frame(name))
        if kind is None:  # fixed: the child joins the parent's joint
            add_frame(model, name, carrier[parent][0], at, pin.FrameType.FIXED_JOINT)
            carrier[child] = (carrier[parent][0], at * self.frame(name).actInv(self.frame(child)))
        else:
            axis = self.axis(joint, "axis", where) if kind != "spherical" else None
            axis2 = self.axis(joint, "axis2", where) if kind == "universal" else None
            jid = add_joint(model, name, carrier[parent][0], joint_model(kind, axis, axis2), at)
            carrier[child] = (jid, self.frame(name).actInv(self.frame(child)))
            springs += self._springs(joint, name, kind, where)
            if kind != "universal":
                guess[name] = 0.0 if kind in ("revolute", "prismatic") else (0.0, 0.0, 0.0)
        add_body(model, child, *carrier[child], self._inertia(child))

    def _dynamics(self, joint: ET.Element, tag: str, where: str) -> tuple[float, float, float]:
        """(stiffness, reference, damping) of an axis's `<dynamics>` (zeros where absent)."""
        dynamics = joint.find(f"{tag}/dynamics")
        if dynamics is None:
            return 0.0, 0.0, 0.0
        return tuple(_number(dynamics, t, where, 0.0) for t in ("spring_stiffness", "spring_reference", "damping"))

    def _springs(self, joint: ET.Element, name: str, kind: str, where: str) -> list[JointSpring]:
        tags = ("axis", "axis2") if kind == "universal" else ("axis",)
        values = [self._dynamics(joint, tag, where) for tag in tags]
        stiffness, reference, damping = values[0]
        if kind in ("spherical", "universal") and (any(v[0] for v in values) or len({v[2] for v in values}) > 1):
            raise MalformedDescription(where, f"a {kind} joint's spring (or unequal damping on its axes) is not read")
        return [JointSpring(name, stiffness, reference, 0.0, damping)] if stiffness or damping else []

    def _cut(self, model: pin.Model, name: str, ends: tuple[str, str], carrier: dict) -> LoopClosure:
        joint, where = self.items["joint"][name], f"SDF joint {name!r}"
        kind = KINDS[joint.get("type")][1]
        tags = ("axis", "axis2") if kind == "hooke" else ("axis",)
        if any(self._dynamics(joint, tag, where)[0] for tag in tags):
            raise MalformedDescription(where, "a spring on a cut joint (one closing a loop) is not read")
        for side, link in zip("ab", ends, strict=True):
            add_frame(model, f"{name}_{side}", carrier[link][0], self._in(carrier, link, self.frame(name)))
        axis = self.axis(joint, "axis", where) if kind in ("revolute", "prismatic", "hooke") else None
        axis2 = self.axis(joint, "axis2", where) if kind == "hooke" else None
        return LoopClosure(name, kind, f"{name}_a", f"{name}_b", None if kind == "hooke" else axis,
                           axis if kind == "hooke" else None, axis2, explicit_rows=False)

    def _gearbox(self, name: str, ends: tuple[str, str], tree: dict, all_ends: dict) -> Coupling:
        joint, where = self.items["joint"][name], f"SDF joint {name!r}"
        reference = (joint.findtext("gearbox_reference_body") or "").strip()
        if reference not in self.items["link"]:
            raise MalformedDescription(where, f"gearbox_reference_body {reference!r} is not a link of the model")
        ratio = _number(joint, "gearbox_ratio", where, None)
        R = self.frame(name).rotation
        terms = []
        for link, tag in zip(ends, ("axis", "axis2"), strict=True):
            axis = R @ self.axis(joint, tag, where)
            found = [(j, 1.0 if all_ends[j][0] == reference else -1.0) for j in tree.values()
                     if set(all_ends[j]) == {reference, link} and KINDS[self.items["joint"][j].get("type")][0] == "revolute"]
            if not found:
                raise MalformedDescription(where, f"no revolute tree joint between gearbox_reference_body {reference!r} "
                                           f"and {link!r}")
            j, sign = found[0]
            along = float(axis @ (self.frame(j).rotation @ self.axis(self.items["joint"][j], "axis", where)))
            if abs(abs(along) - 1.0) > 1e-9:
                raise MalformedDescription(where, f"<{tag}> is not the axis of joint {j!r}")
            terms.append(((j, sign * float(np.sign(along))),))
        return Coupling(name, terms[1], terms[0], (0.0, -ratio))
