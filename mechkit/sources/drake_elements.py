"""Loop closures written the way Drake and Gazebo write them in a URDF, read into `LoopClosure` records.

- `<drake:ball_constraint>` (Drake's URDF extension): point P of body A (`p_AP`, in A's frame, m) and
  point Q of body B (`p_BQ`) kept together: a spherical cut.
- `<drake:linear_bushing_rpy>` between two frames (Drake's `<frame name link xyz rpy>` or links; an
  SDFormat model's too, `bushings`): read as a rigid cut on its stiff directions, the others left free
  (`stiff_directions`); marked `mechkit:compliant="true"` (`compliant`, `load(bushings="compliant")`) its
  frames only, the simulator's force element (`mechkit.forces.bushing`) then acting between them.
- `<gazebo><joint type parent child pose axis>` (the Gazebo tutorials' way to close a URDF loop): an
  SDFormat joint; its frame is `pose` in the child link's frame (SDFormat's default), its axis in that
  frame; the parent side is where that frame is at the URDF's zero configuration (as Gazebo places it
  when the model spawns). revolute, prismatic, ball and fixed are read, universal and revolute2 (`axis` then
  `axis2`, perpendicular) as a Hooke cut; other types are refused by name.

A link `world` joints name without declaring it is declared (`declare_world`): the implicit ground of
Drake and Gazebo; with the world a link, every other link without a parent joint floats, as Drake's
MultibodyPlant leaves a body no joint holds (a `floating` joint from the world, `<link>_root_joint`, at
the identity: Drake's default free-body pose). Each cut gets two frames, added to the tree as massless
links fixed to the bodies (`<cut>_a`, `<cut>_b`), so the closure is the same record `<mechkit:loop>`
gives (`mechkit.sources.urdf`).
"""

from __future__ import annotations

import dataclasses
import xml.etree.ElementTree as ET
from collections.abc import Collection
from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidArgument, MalformedDescription
from mechkit.core import LoopClosure
from mechkit.sources.closure_elements import DRAKE
from mechkit.sources.description import Description

#: A bushing direction is stiff (closed) when its stiffness exceeds this fraction of the largest of its kind
#: (torques in N m/rad, forces in N/m compared among themselves), else free (ours). Drake's examples stand
#: a pin for a bushing stiff in five directions and zero (or orders of magnitude softer) in the sixth; a
#: thousandth keeps any such stand-in a joint and a bushing meant to be compliant everywhere a weld.
BUSHING_RATIO = 1e-3

#: The attribute that makes a bushing compliant (a force element, `mechkit.forces.bushing`) instead of a cut;
#: in mechkit's loop namespace (`mechkit.sources.urdf.LOOP_NAMESPACE`).
COMPLIANT = "{https://mechkit.dev/loop}compliant"

#: SDFormat joint type -> mechkit cut kind.
GAZEBO_KINDS = {"revolute": "revolute", "prismatic": "prismatic", "ball": "spherical", "fixed": "weld"}
GAZEBO_KINDS |= {"universal": "hooke", "revolute2": "hooke"}
ET.register_namespace("drake", DRAKE)  # the text `compliant` writes keeps Drake's prefix


def declare_world(root: ET.Element) -> bool:
    """Declare the link `world` when joints name it undeclared (Drake and Gazebo take it as the ground), and
    float every other root link from it (Drake's free bodies; see the module docstring).

    Args:
        root: the URDF's `<robot>` element; a `<link name="world"/>` is prepended to it and `floating`
            joints appended if needed.

    Returns:
        Whether `root` changed.
    """
    joints = root.findall("joint")
    ends = [(j.find("parent"), j.find("child")) for j in joints]
    named = {end.get("link") for pair in ends for end in pair if end is not None}  # missing: check_tree names it
    links = [link.get("name") for link in root.findall("link")]
    if "world" not in named and "world" not in links:
        return False
    changed = "world" not in links
    if changed:
        root.insert(0, ET.Element("link", name="world"))
    children = {child.get("link") for _, child in ends if child is not None}
    for link in links:
        if link != "world" and link not in children:
            joint = ET.SubElement(root, "joint", name=f"{link}_root_joint", type="floating")
            ET.SubElement(joint, "parent", link="world")
            ET.SubElement(joint, "child", link=link)
            changed = True
    return changed


def read_tool_closures(root: ET.Element) -> list[LoopClosure]:
    """Read the Drake ball constraints and Gazebo joints of a URDF into closures, adding their frames.

    Args:
        root: the URDF's `<robot>` element; the cut frames are appended to it as links and fixed joints.

    Returns:
        The closures, Drake's then Gazebo's, each in document order.

    Raises:
        MalformedDescription: a missing or malformed attribute, a body that is not a link, or a Gazebo
            joint of a type mechkit cannot cut.
    """
    links = {link.get("name") for link in root.findall("link")}
    out = []
    for name, body_a, p_ap, body_b, p_bq in ball_constraints(root, links):
        _add_frame(root, f"{name}_a", body_a, p_ap, np.eye(3))
        _add_frame(root, f"{name}_b", body_b, p_bq, np.eye(3))
        out.append(LoopClosure(name, "spherical", f"{name}_a", f"{name}_b", explicit_rows=False))
    for bushing in bushings(root):
        cut = _bushing(root, bushing, links)
        if not bushing.compliant:
            out.append(cut)
    for gazebo in root.findall("gazebo"):
        for element in gazebo.findall("joint"):
            out.append(_gazebo_joint(root, element, links))
    return out


def _gazebo_joint(root: ET.Element, element: ET.Element, links: set[str]) -> LoopClosure:
    name = element.get("name") or "gazebo_joint"
    where = f"gazebo/joint {name!r}"
    kind = GAZEBO_KINDS.get(element.get("type", ""))
    if kind is None:
        raise MalformedDescription(where, f"type {element.get('type')!r}: mechkit cuts {tuple(GAZEBO_KINDS)}")
    ends = {}
    for tag in ("parent", "child"):
        text = (element.findtext(tag) or "").strip()
        if text not in links:
            raise MalformedDescription(where, f"{tag} {text!r} is not a link of the URDF")
        ends[tag] = text
    pose = np.zeros(6)
    if element.find("pose") is not None:
        pose = _numbers(element.findtext("pose"), 6, f"{where} pose")
    joint_in_child = _transform(pose[:3], pose[3:])
    world = _zero_poses(root)
    joint_in_parent = np.linalg.solve(world[ends["parent"]], world[ends["child"]] @ joint_in_child)
    axes = []
    for tag in ("axis", "axis2")[: {"revolute": 1, "prismatic": 1, "hooke": 2}.get(kind, 0)]:
        axis = _numbers(element.findtext(f"{tag}/xyz") or "", 3, f"{where} {tag}/xyz")
        if np.linalg.norm(axis) == 0:
            raise MalformedDescription(where, f"{tag}/xyz is zero")
        axes.append(axis / np.linalg.norm(axis))
    if len(axes) == 2 and abs(float(axes[0] @ axes[1])) > 1e-9:
        raise MalformedDescription(where, "axis and axis2 are not perpendicular: a universal joint's must be")
    _add_frame(root, f"{name}_a", ends["parent"], joint_in_parent[:3, 3], joint_in_parent[:3, :3])
    _add_frame(root, f"{name}_b", ends["child"], joint_in_child[:3, 3], joint_in_child[:3, :3])
    if kind == "hooke":  # axis on the parent side, axis2 on the child's (sdformat.org's joint spec)
        return LoopClosure(name, kind, f"{name}_a", f"{name}_b", None, *axes, explicit_rows=False)
    return LoopClosure(name, kind, f"{name}_a", f"{name}_b", axes[0] if axes else None, explicit_rows=False)


def ball_constraints(parent: ET.Element, links: Collection[str]) -> list[tuple[str, str, np.ndarray, str, np.ndarray]]:
    """The `drake:ball_constraint` children of a URDF `<robot>` (values in attributes `name`, `value`) or
    an SDFormat `<model>` (values as text).

    Args:
        parent: the `<robot>` or `<model>` element.
        links: the names of its links.

    Returns:
        (cut name "ball_<A>_<B>", body A, p_AP (3,) m in A's frame, body B, p_BQ (3,) m in B's frame) each.

    Raises:
        MalformedDescription: a body that is not a link, or a point that is not three finite numbers.
    """
    out = []
    for k, element in enumerate(parent.findall(f"{{{DRAKE}}}ball_constraint"), 1):
        where = f"drake:ball_constraint #{k}"
        values = {}
        for tag in ("body_A", "body_B", "p_AP", "p_BQ"):
            child = element.find(f"{{{DRAKE}}}ball_constraint_{tag}")
            if child is None:
                raise MalformedDescription(where, f"missing drake:ball_constraint_{tag}")
            values[tag] = (child.get("name" if tag.startswith("body") else "value") or child.text or "").strip()
        for tag in ("body_A", "body_B"):
            if values[tag] not in links:
                raise MalformedDescription(where, f"drake:ball_constraint_{tag} {values[tag]!r} is not a link")
        points = [_numbers(values[tag], 3, f"{where} drake:ball_constraint_{tag}") for tag in ("p_AP", "p_BQ")]
        name = f"ball_{values['body_A']}_{values['body_B']}"
        out.append((name, values["body_A"], points[0], values["body_B"], points[1]))
    return out


def stiff_directions(torque: np.ndarray, force: np.ndarray) -> tuple[str, np.ndarray | None]:
    """The cut a bushing stands for: its stiff directions closed, its free ones (`BUSHING_RATIO`) left free.

    Args:
        torque: (3,) torque stiffness about frame A's x, y, z (N m/rad, >= 0).
        force: (3,) force stiffness along them (N/m, >= 0).

    Returns:
        (kind, axis): "weld", "spherical", ("revolute", free rotation axis) or ("prismatic", free
        translation axis), the axis in frame A; None where the pattern is no such joint.
    """
    free_t, free_f = (k <= BUSHING_RATIO * k.max() for k in (torque, force))
    if force.max() <= 0 or free_f.sum() > 1 or (free_f.any() and free_t.any()):
        return "", None
    if free_f.any():
        return "prismatic", np.eye(3)[np.argmax(free_f)]
    kinds = {0: "weld", 1: "revolute", 3: "spherical"}
    kind = kinds.get(int(free_t.sum()), "")
    return kind, np.eye(3)[np.argmax(free_t)] if kind == "revolute" else None


@dataclass(frozen=True)
class Bushing:
    """A `drake:linear_bushing_rpy` (Drake's LinearBushingRollPitchYaw) as written.

    Attributes:
        name: "bushing_<A>_<C>", the cut's and the force element's name.
        frame_a: the name of frame A (a URDF `<frame>` or link, an SDFormat frame or link).
        frame_c: the name of frame C.
        torque_stiffness: (3,) N m/rad about A's x, y, z (roll, pitch, yaw); torque_damping: N m s/rad.
        force_stiffness: (3,) N/m along them; force_damping: N s/m.
        compliant: marked `mechkit:compliant="true"` (`compliant`): a force element, not a cut.
    """

    name: str
    frame_a: str
    frame_c: str
    torque_stiffness: np.ndarray
    torque_damping: np.ndarray
    force_stiffness: np.ndarray
    force_damping: np.ndarray
    compliant: bool = False

    def cut(self) -> tuple[str, np.ndarray | None]:
        """The cut it stands for when read rigid (`stiff_directions`).

        Returns:
            (kind, axis in frame A or None).

        Raises:
            MalformedDescription: a pattern that is no joint mechkit closes.
        """
        kind, axis = stiff_directions(self.torque_stiffness, self.force_stiffness)
        if not kind:
            raise MalformedDescription(
                f"drake:linear_bushing_rpy {self.frame_a!r}-{self.frame_c!r}",
                f"torque stiffness {self.torque_stiffness.tolist()}, force stiffness "
                f"{self.force_stiffness.tolist()}: its stiff directions (above {BUSHING_RATIO} of the largest of "
                "their kind) make no joint mechkit closes (weld, revolute, prismatic, spherical)",
            )
        return kind, axis


def bushings(parent: ET.Element) -> list[Bushing]:
    """The `drake:linear_bushing_rpy` children of a URDF `<robot>` (values in attributes `name`, `value`) or
    an SDFormat `<model>` (values as text), in document order.

    Args:
        parent: the `<robot>` or `<model>` element.

    Returns:
        The bushings (frames named, not resolved).

    Raises:
        MalformedDescription: a missing frame or value, a value that is not three finite numbers, a negative
            stiffness or damping.
    """
    out = []
    for element in parent.findall(f"{{{DRAKE}}}linear_bushing_rpy"):
        frames = []
        for side in "AC":
            child = element.find(f"{{{DRAKE}}}bushing_frame{side}")
            name = (child.get("name") or child.text or "").strip() if child is not None else ""
            if not name:
                raise MalformedDescription("drake:linear_bushing_rpy", f"missing drake:bushing_frame{side}")
            frames.append(name)
        where = f"drake:linear_bushing_rpy {frames[0]!r}-{frames[1]!r}"
        values = []
        for kind in ("torque_stiffness", "torque_damping", "force_stiffness", "force_damping"):
            child = element.find(f"{{{DRAKE}}}bushing_{kind}")
            if child is None:
                raise MalformedDescription(where, f"missing drake:bushing_{kind}")
            values.append(
                _numbers((child.get("value") or child.text or "").strip(), 3, f"{where} drake:bushing_{kind}")
            )
            if np.any(values[-1] < 0):
                raise MalformedDescription(where, f"a negative {kind.replace('_', ' ')}")
        name = f"bushing_{frames[0]}_{frames[1]}"
        out.append(Bushing(name, *frames, *values, element.get(COMPLIANT) == "true"))
    return out


def _bushing(root: ET.Element, bushing: Bushing, links: set[str]) -> LoopClosure:
    """The rigid cut of a URDF's bushing, its frames added (a `<frame name link xyz rpy>` or a link)."""
    frames = {f.get("name"): f for f in root.findall("frame")}
    poses = []
    for name in (bushing.frame_a, bushing.frame_c):
        if name in frames:
            frame = frames[name]
            xyz, rpy = (_numbers(frame.get(a, "0 0 0"), 3, f"frame {name!r} {a}") for a in ("xyz", "rpy"))
            poses.append((frame.get("link"), _transform(xyz, rpy)))
        elif name in links:
            poses.append((name, np.eye(4)))
        else:
            raise MalformedDescription("drake:linear_bushing_rpy", f"frame {name!r} is not a frame or link of the URDF")
        if poses[-1][0] not in links:
            raise MalformedDescription(
                "drake:linear_bushing_rpy", f"frame {name!r}: link {poses[-1][0]!r} is not a link of the URDF"
            )
    kind, axis = ("weld", None) if bushing.compliant else bushing.cut()
    for side, (link, pose) in zip("ab", poses):
        _add_frame(root, f"{bushing.name}_{side}", link, pose[:3, 3], pose[:3, :3])
    return LoopClosure(bushing.name, kind, f"{bushing.name}_a", f"{bushing.name}_b", axis, explicit_rows=False)


def compliant(description: Description) -> Description:
    """The description with its URDF's bushings compliant: marked `COMPLIANT` in its text (where the
    simulator's force elements read them, `mechkit.forces.described`), their cuts left open (their frames
    stay).

    Args:
        description: a description read with rigid bushings.

    Returns:
        The description changed (itself where it has no bushing).

    Raises:
        InvalidArgument: its bushings are not in a URDF text (an SDFormat file's, or a URDF's whose Drake
            joints made its tree a built model): those are read rigid only.
    """
    root = ET.fromstring(description.urdf) if description.urdf else None
    found = bushings(root) if root is not None else []
    if not found:
        source = description.source
        text = source.read_text() if source is not None else ""
        if "linear_bushing_rpy" in text or any(c.name.startswith("bushing_") for c in description.closures or ()):
            raise InvalidArgument(
                "bushings",
                "compliant",
                f"{source.name if source else 'the description'}: compliant bushings are read from a URDF or xacro "
                f"tree of URDF joints; this {description.format} file's are read rigid only",
            )
        return description
    for element in root.iter(f"{{{DRAKE}}}linear_bushing_rpy"):
        element.set(COMPLIANT, "true")
    names = {b.name for b in found}
    return dataclasses.replace(
        description,
        urdf=ET.tostring(root, encoding="unicode"),
        closures=tuple(c for c in description.closures or () if c.name not in names),
    )


def _numbers(text: str, n: int, where: str) -> np.ndarray:
    try:
        values = np.array([float(v) for v in text.split()])
    except ValueError:
        values = np.zeros(0)
    if values.shape != (n,) or not np.all(np.isfinite(values)):
        raise MalformedDescription(where, f"{text!r} is not {n} finite numbers")
    return values


def _transform(xyz: np.ndarray, rpy: np.ndarray) -> np.ndarray:
    """Homogeneous transform of an `xyz rpy` origin (URDF and SDFormat: R = Rz(y) Ry(p) Rx(r))."""
    c, s = np.cos(rpy), np.sin(rpy)
    rx = np.array([[1, 0, 0], [0, c[0], -s[0]], [0, s[0], c[0]]])
    ry = np.array([[c[1], 0, s[1]], [0, 1, 0], [-s[1], 0, c[1]]])
    rz = np.array([[c[2], -s[2], 0], [s[2], c[2], 0], [0, 0, 1]])
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = rz @ ry @ rx, xyz
    return out


def _zero_poses(root: ET.Element) -> dict[str, np.ndarray]:
    """Each link's pose in the root link's frame at the zero configuration (the tree is already checked)."""
    parent_of = {}
    for joint in root.findall("joint"):
        origin = joint.find("origin")
        xyz, rpy = (
            _numbers(origin.get(a, "0 0 0") if origin is not None else "0 0 0", 3, "origin") for a in ("xyz", "rpy")
        )
        parent_of[joint.find("child").get("link")] = (joint.find("parent").get("link"), _transform(xyz, rpy))
    poses: dict[str, np.ndarray] = {}

    def pose(link: str) -> np.ndarray:
        if link not in poses:
            parent, origin = parent_of.get(link, (None, None))
            poses[link] = np.eye(4) if parent is None else pose(parent) @ origin
        return poses[link]

    return {link.get("name"): pose(link.get("name")) for link in root.findall("link")}


def _add_frame(root: ET.Element, name: str, body: str, xyz: np.ndarray, rotation: np.ndarray) -> None:
    """A massless link `name` fixed to `body` at `xyz` (m) with orientation `rotation`, both in body's frame;
    kept where the text has it already on `body` (mechkit wrote it: a compliant bushing's frames)."""
    if root.find(f"link[@name='{name}']") is not None:
        if root.find(f"joint[@name='{name}_fixed']/parent[@link='{body}']") is None:
            raise MalformedDescription(f"link {name!r}", f"the name of a frame mechkit adds on {body!r}: rename it")
        return
    pitch = np.arcsin(np.clip(-rotation[2, 0], -1.0, 1.0))
    roll, yaw = np.arctan2(rotation[2, 1], rotation[2, 2]), np.arctan2(rotation[1, 0], rotation[0, 0])
    ET.SubElement(root, "link", name=name)
    joint = ET.SubElement(root, "joint", name=f"{name}_fixed", type="fixed")
    ET.SubElement(joint, "parent", link=body)
    ET.SubElement(joint, "child", link=name)
    fmt = " ".join
    ET.SubElement(
        joint, "origin", xyz=fmt(repr(float(v)) for v in xyz), rpy=fmt(repr(float(v)) for v in (roll, pitch, yaw))
    )
