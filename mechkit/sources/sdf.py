"""An SDFormat file (`.sdf`), read with an XML parser (the PyPI build of Pinocchio has no SDF parser)
into a Pinocchio model with closure records.

The file holds one `<model>` of links, joints and `<frame>`s, in any order (the spec,
sdformat.org/spec?ver=1.9&elem=model, puts none on a model's children), and nested `<model>`s, read as
libsdformat reads them: flattened into it, their names scoped by `::` (`mechkit.sources.sdf_nested`;
`<include>` and world files are refused by name). Its joints may form a graph; it becomes a spanning tree
plus cut joints:

- the tree joint of a link is, among the joints whose child it is, the one named in
  `parent_guidance`, else the first in file order (Pinocchio's SDF parser chooses so); its other
  parent joints are cuts. A link no joint leads to is a root: a free-flyer (`root_joint`, or
  `<link>_root_joint` when there are several). A `<static>` model (nothing moves) is refused.
- a cut joint is a `LoopClosure` between frames `<joint>_a` on its parent link and `<joint>_b` on its
  child link, both at the joint's frame in the file's configuration: revolute / continuous ->
  revolute, prismatic -> prismatic, ball -> spherical, fixed -> weld, universal and revolute2 -> Hooke.
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
Tree joints: revolute and continuous (one coordinate, an angle), prismatic, ball, universal and revolute2
(sdformat.org/spec?ver=1.9&elem=joint: two revolute axes in series, `axis` then `axis2`; read as one
universal joint, so their axes must be perpendicular: refused by name otherwise), fixed
(the child's inertia joins the parent's joint). Inertia: `<inertial>` in the link frame, SDFormat's
defaults where absent (1 kg, unit inertia). Springs: `<dynamics>` `spring_stiffness`,
`spring_reference`, `damping` of tree joints; a cut joint's damping is not read (no coordinate
carries it), its stiffness is refused. Limits, friction, plugins and geometry are not read. Drake's
`drake:ball_constraint` and `drake:linear_bushing_rpy` are cuts, as in a URDF (`mechkit.sources.drake_elements`).
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
from mechkit.sources.drake_elements import ball_constraints, bushings
from mechkit.sources.physical import check_body
from mechkit.sources.pinocchio_tree import add_body, add_frame, add_joint, joint_model, tree_urdf
from mechkit.sources.sdf_frames import MODEL, SdfFrames, boolean, number, sdf_version
from mechkit.sources.sdf_nested import flattened
from mechkit.sources.urdf import parse_xml

#: SDFormat joint type -> Pinocchio joint kind (tree) and cut kind.
KINDS = {
    "revolute": ("revolute", "revolute"),
    "continuous": ("revolute", "revolute"),
    "prismatic": ("prismatic", "prismatic"),
    "ball": ("spherical", "spherical"),
    "universal": ("universal", "hooke"),
    "revolute2": ("universal", "hooke"),
    "fixed": (None, "weld"),
    "gearbox": (None, None),
}


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
        raise MalformedDescription(
            str(path),
            f"expected one <model> under <sdf>, found {len(models)}"
            + (" and a <world>" if root.find("world") is not None else ""),
        )
    version = sdf_version(root, str(path))
    return _Reader(flattened(models[0], version), version, tuple(parent_guidance)).description(path)


class _Reader(SdfFrames):
    """One SDFormat model: its frames, tree, cuts, couplings and springs."""

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
        tree = {
            link: next((j for j in options if j in self.guidance), options[0])
            for link, options in parents.items()
            if options
        }
        if boolean(self.element.findtext("static"), f"SDF model {self.name!r}", "<static>"):
            raise MalformedDescription(f"SDF model {self.name!r}", "<static> is true: nothing in it moves")
        roots = [link for link in self.items["link"] if link not in tree]
        model = pin.Model()
        model.name = self.name
        add_body(model, "world", 0, pin.SE3.Identity(), pin.Inertia.Zero())
        carrier: dict[str, tuple[int, pin.SE3]] = {"world": (0, pin.SE3.Identity())}
        guess: dict[str, float | tuple[float, ...]] = {}
        springs: list[JointSpring] = []
        # depth first, a root's free-flyer just before its subtree: Pinocchio's algorithms take a subtree as
        # contiguous joints
        stack = list(reversed(["world", *roots]))
        while stack:
            link = stack.pop()
            if link in roots:
                self._root(model, link, "root_joint" if len(roots) == 1 else f"{link}_root_joint", carrier, guess)
            elif link != "world":
                self._tree_joint(model, tree[link], ends[tree[link]], carrier, springs, guess)
            stack += reversed([c for c, j in tree.items() if ends[j][0] == link])
        lost = [link for link in self.items["link"] if link not in carrier]
        if lost:
            raise MalformedDescription(
                f"SDF link {lost[0]!r}",
                f"links {lost} reach neither the world nor a root: their parent joints form a cycle",
            )
        for name, frame in self.items["frame"].items():  # frames on links (not those on the model frame)
            if frame.get("attached_to", MODEL) != MODEL:
                link = self.link_of(frame.get("attached_to"), "attached_to", f"SDF frame {name!r}")
                add_frame(model, name, carrier[link][0], self._in(carrier, link, self.frame(name)))
        closures = [
            self._cut(model, j, ends[j], carrier)
            for j, joint in joints.items()
            if joint.get("type") != "gearbox" and tree.get(ends[j][1]) != j
        ]
        for cut, link_a, p_ap, link_b, p_bq in ball_constraints(self.element, self.items["link"]):  # Drake's
            for side, link, p in (("a", link_a, p_ap), ("b", link_b, p_bq)):
                at = self._in(carrier, link, self.frame(link) * pin.SE3(np.eye(3), p))
                add_frame(model, f"{cut}_{side}", carrier[link][0], at)
            closures.append(LoopClosure(cut, "spherical", f"{cut}_a", f"{cut}_b", explicit_rows=False))
        for bushing in bushings(self.element):  # Drake's, read as the URDF's are (sources.drake_elements)
            kind, axis = bushing.cut()
            for side, name in (("a", bushing.frame_a), ("b", bushing.frame_c)):
                link = self.link_of(name, "a bushing frame", f"drake:linear_bushing_rpy {bushing.name!r}")
                add_frame(model, f"{bushing.name}_{side}", carrier[link][0], self._in(carrier, link, self.frame(name)))
            closures.append(
                LoopClosure(bushing.name, kind, f"{bushing.name}_a", f"{bushing.name}_b", axis, explicit_rows=False)
            )
        couplings = [
            self._gearbox(j, ends[j], tree, ends) for j, joint in joints.items() if joint.get("type") == "gearbox"
        ]
        actuated = tuple(dict.fromkeys(k.leader[0][0] for k in couplings))
        return Description(
            self.name,
            tree_urdf(model, tuple(closures)),
            actuated,
            {j: 0.0 for j in actuated},
            guess,
            path,
            "sdf",
            closures=tuple(closures),
            model=model,
            couplings=tuple(couplings),
            springs=tuple(springs),
        )

    def _root(self, model: pin.Model, link: str, name: str, carrier: dict, guess: dict) -> None:
        """A free-flyer `name` from the world to a root link, its guess the link's pose in the world."""
        at = self.world * self.frame(link)
        carrier[link] = (add_joint(model, name, 0, pin.JointModelFreeFlyer(), pin.SE3.Identity()), pin.SE3.Identity())
        guess[name] = tuple(float(x) for x in at.translation) + tuple(float(x) for x in pin.log3(at.rotation))
        add_body(model, link, *carrier[link], self._inertia(link))

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
        mass = number(inertial, "mass", where, 1.0)
        tensor = inertial.find("inertia")
        i = {
            k: number(tensor, k, where, 1.0 if k[1] == k[2] else 0.0)
            if tensor is not None
            else (1.0 if k[1] == k[2] else 0.0)
            for k in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")
        }
        I = np.array([[i["ixx"], i["ixy"], i["ixz"]], [i["ixy"], i["iyy"], i["iyz"]], [i["ixz"], i["iyz"], i["izz"]]])
        I = check_body(where, mass, I, i)  # before Pinocchio, which throws on a negative moment
        R = placement.rotation
        return pin.Inertia(mass, placement.translation, R @ I @ R.T)

    def _tree_joint(
        self, model: pin.Model, name: str, ends: tuple[str, str], carrier: dict, springs: list, guess: dict
    ) -> None:
        joint, (parent, child) = self.items["joint"][name], ends
        where, kind = f"SDF joint {name!r}", KINDS[self.items["joint"][name].get("type")][0]
        at = self._in(carrier, parent, self.frame(name))
        if kind is None:  # fixed: the child joins the parent's joint
            add_frame(model, name, carrier[parent][0], at, pin.FrameType.FIXED_JOINT)
            carrier[child] = (carrier[parent][0], at * self.frame(name).actInv(self.frame(child)))
        else:
            axis, axis2 = self._axes(joint, kind == "universal", where) if kind != "spherical" else (None, None)
            jid = add_joint(model, name, carrier[parent][0], joint_model(kind, axis, axis2), at)
            carrier[child] = (jid, self.frame(name).actInv(self.frame(child)))
            springs += self._springs(joint, name, kind, where)
            if kind != "universal":
                guess[name] = 0.0 if kind in ("revolute", "prismatic") else (0.0, 0.0, 0.0)
        add_body(model, child, *carrier[child], self._inertia(child))

    def _axes(self, joint: ET.Element, two: bool, where: str) -> tuple[np.ndarray, np.ndarray | None]:
        """A joint's `axis` and, for a universal or revolute2 joint (`two`), its `axis2`, perpendicular to it.

        Raises:
            MalformedDescription: an axis missing or zero, or two axes not perpendicular (Pinocchio's universal
                joint and mechkit's Hooke cut assume they are).
        """
        axis = self.axis(joint, "axis", where)
        if not two:
            return axis, None
        axis2 = self.axis(joint, "axis2", where)
        if abs(float(axis @ axis2)) > 1e-9:
            raise MalformedDescription(
                where, f"axis and axis2 are not perpendicular (cosine {axis @ axis2:.3g}): read as a universal joint"
            )
        return axis, axis2

    def _dynamics(self, joint: ET.Element, tag: str, where: str) -> tuple[float, float, float]:
        """(stiffness, reference, damping) of an axis's `<dynamics>` (zeros where absent)."""
        dynamics = joint.find(f"{tag}/dynamics")
        if dynamics is None:
            return 0.0, 0.0, 0.0
        return tuple(number(dynamics, t, where, 0.0) for t in ("spring_stiffness", "spring_reference", "damping"))

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
        axis, axis2 = (
            self._axes(joint, kind == "hooke", where) if kind != "spherical" and kind != "weld" else (None, None)
        )
        return LoopClosure(
            name,
            kind,
            f"{name}_a",
            f"{name}_b",
            None if kind == "hooke" else axis,
            axis if kind == "hooke" else None,
            axis2,
            explicit_rows=False,
        )

    def _gearbox(self, name: str, ends: tuple[str, str], tree: dict, all_ends: dict) -> Coupling:
        joint, where = self.items["joint"][name], f"SDF joint {name!r}"
        reference = (joint.findtext("gearbox_reference_body") or "").strip()
        if reference not in self.items["link"]:
            raise MalformedDescription(where, f"gearbox_reference_body {reference!r} is not a link of the model")
        ratio = number(joint, "gearbox_ratio", where, None)
        R = self.frame(name).rotation
        terms = []
        for link, tag in zip(ends, ("axis", "axis2"), strict=True):
            axis = R @ self.axis(joint, tag, where)
            found = [
                (j, 1.0 if all_ends[j][0] == reference else -1.0)
                for j in tree.values()
                if set(all_ends[j]) == {reference, link} and KINDS[self.items["joint"][j].get("type")][0] == "revolute"
            ]
            if not found:
                raise MalformedDescription(
                    where, f"no revolute tree joint between gearbox_reference_body {reference!r} and {link!r}"
                )
            j, sign = found[0]
            along = float(axis @ (self.frame(j).rotation @ self.axis(self.items["joint"][j], "axis", where)))
            if abs(abs(along) - 1.0) > 1e-9:
                raise MalformedDescription(where, f"<{tag}> is not the axis of joint {j!r}")
            terms.append(((j, sign * float(np.sign(along))),))
        return Coupling(name, terms[1], terms[0], (0.0, -ratio))
