"""A URDF with `<mechkit:loop>` elements: the loops read with an XML parser into `LoopClosure` records,
its `<mimic>` joints into `Coupling` rows, its actuators from its `<transmission>` elements, its tree
built by Pinocchio.

Loop closures are declared inside the URDF as `<mechkit:loop name type frame_a frame_b axis rows/>`
(namespace `LOOP_NAMESPACE`); urdfdom and other URDF consumers ignore the element. frame_a and frame_b
name a link or a joint of the URDF (Pinocchio gives both a frame).

A joint's `<mimic joint="leader" multiplier="m" offset="o"/>` (defaults 1 and 0) is the coupling row
x_joint = m x_leader + o (rad or m); the tree keeps the mimic joint as an ordinary joint (Pinocchio's
`mimic=False`), so the row is what ties it (`mechkit.sources.urdf_mimics`).
"""

from __future__ import annotations

import os
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription
from mechkit.core import LOOP_KINDS, ROW_SETS, JointSpring, LoopClosure
from mechkit.sources.description import Description, read_text
from mechkit.sources.drake_elements import declare_world, read_tool_closures
from mechkit.sources.drake_joints import placeholders, with_joints
from mechkit.sources.onshape_closures import closing_frames
from mechkit.sources.urdf_checks import check_inertias, check_tree
from mechkit.sources.urdf_mimics import parse_mimics
from mechkit.sources.urdf_struts import parse_struts

LOOP_NAMESPACE = "https://mechkit.dev/loop"
#: Elements of the loop namespace mechkit knows (`home`: an input value of the default assembly; `guess`: a
#: joint value near which it is sought, which picks the assembly branch; `spring`: a joint spring; `strut`: a
#: point-to-point spring, damper and force (`mechkit.sources.urdf_struts`, read by the simulator); `beam`,
#: `elastic_joint`: elastic data, read by `mechkit.elastic` and ignored by the rigid pipeline). Any other one
#: is a `MalformedDescription`.
KNOWN_ELEMENTS = ("loop", "home", "guess", "spring", "strut", "beam", "elastic_joint")
#: Local names that declare a loop in some convention; outside the loop namespace they are an error.
LOOP_LIKE = ("loop", "loops", "closure", "closed_loop", "loop_closure", "constraint", "cut")


def read_urdf(path: Path) -> Description:
    """The description in a URDF file (see `describe_urdf`).

    Args:
        path: the file.

    Returns:
        The description.

    Raises:
        MalformedDescription: the file cannot be read, or its URDF is invalid (see `describe_urdf`).
    """
    return describe_urdf(read_text(path), path, "urdf")


def describe_urdf(urdf: str, source: Path | None, fmt: str, params: dict[str, str] | None = None) -> Description:
    """Check a URDF text (tree, inertias, loop elements, home) and read its actuators and mimic couplings.

    Args:
        urdf: the URDF text.
        source: the file it came from, if any.
        fmt: its format's name ("urdf", "xacro", ...).
        params: the xacro arguments it was rendered with, if any.

    Returns:
        The description: the tree URDF (the built model instead with Drake's joint types), its loops,
        actuators, springs and home.

    Raises:
        MalformedDescription: see `mechkit.sources.urdf_checks`, `mechkit.sources.urdf.parse_loops`,
            `mechkit.sources.urdf_mimics.parse_mimics`, `mechkit.sources.onshape_closures.closing_frames`.
    """
    where = str(source) if source is not None else "urdf"
    root = parse_xml(urdf, where)
    drake_joints = placeholders(root)  # Drake's joint types, put in the built tree (sources.drake_joints)
    links = 0 if drake_joints else len(root.findall("link"))
    grounded = declare_world(root)  # Drake's and Gazebo's ground, free bodies, closures (sources.drake_elements)
    check_tree(root)
    check_inertias(root)
    closures = tuple(parse_loops(root))
    closures += closing_frames(root, closures)  # onshape-to-robot's closing_* frames
    tool_closures = read_tool_closures(root)
    if tool_closures or grounded or len(root.findall("link")) != links:
        closures, urdf = closures + tuple(tool_closures), ET.tostring(root, encoding="unicode")
    joints = moving_joints(root)
    home, guess = parse_home(root), parse_home(root, "guess")
    for tag, values in (("home", home), ("guess", guess)):
        for joint in values:
            if joint not in joints:
                raise MalformedDescription(f"mechkit:{tag} {joint!r}", "not a moving joint of the URDF")
    name = root.get("name") or (source.name.split(".")[0] if source else "urdf")
    springs = parse_springs(root)
    parse_struts(root, {link.get("name") for link in root.findall("link")})  # refused at load, by name
    cut_joints = {c.name for c in closures if c.kind in ("revolute", "prismatic")}  # a spring acts on their value
    for spring in springs:
        if spring.joint not in joints and spring.joint not in cut_joints:
            raise MalformedDescription(
                f"mechkit:spring {spring.joint!r}", "not a moving joint of the URDF nor a revolute or prismatic loop"
            )
    return Description(
        name,
        None if drake_joints else urdf,
        transmissions(root, joints),
        home,
        guess,
        source,
        fmt,
        dict(params or {}),
        closures,
        couplings=parse_mimics(root),
        springs=springs,
        pose="<mechkit:guess>" if guess else "the joints' zero",
        model=with_joints(build_model(urdf), drake_joints) if drake_joints else None,
    )


def moving_joints(root: ET.Element) -> set[str]:
    """Names of the URDF's joints that are not fixed.

    Args:
        root: the URDF's `<robot>` element.

    Returns:
        The joint names.
    """
    return {j.get("name") for j in root.findall("joint") if j.get("type") != "fixed"}


def transmissions(root: ET.Element, joints: set[str]) -> tuple[str, ...]:
    """Joints driven by `<transmission>` elements (ROS format: `<transmission><joint name=.../>`).

    Args:
        root: the URDF's <robot> element.
        joints: its moving joints.

    Returns:
        The driven joints, in order of appearance.

    Raises:
        MalformedDescription: a transmission names a joint that is not a moving joint.
    """
    out: list[str] = []
    for transmission in root.findall("transmission"):
        for joint in transmission.findall("joint"):
            name = joint.get("name")
            if name not in joints:
                raise MalformedDescription(
                    f"transmission {transmission.get('name')!r}", f"joint {name!r} is not a moving joint of the URDF"
                )
            if name not in out:
                out.append(name)
    return tuple(out)


def parse_xml(text: str, where: str = "urdf") -> ET.Element:
    """The root element of an XML text.

    Args:
        text: the XML text.
        where: what it is, for the error.

    Returns:
        The root element.

    Raises:
        MalformedDescription: not well-formed XML.
    """
    try:
        return ET.fromstring(text.encode())
    except ET.ParseError as err:
        raise MalformedDescription(where, f"not well-formed XML: {err}") from None


def check_loop_elements(root: ET.Element) -> None:
    """Refuse loop declarations mechkit would otherwise drop without a word.

    Args:
        root: the URDF's <robot> element.

    Raises:
        MalformedDescription: an element in a namespace that looks like mechkit's but is not
            `LOOP_NAMESPACE` (a mistyped URI), an unknown element of the loop namespace, or a
            loop-like element (`LOOP_LIKE`) outside it.
    """
    for element in root.iter():
        if not isinstance(element.tag, str):
            continue
        uri, _, local = element.tag[1:].partition("}") if element.tag.startswith("{") else ("", "", element.tag)
        if uri == LOOP_NAMESPACE:
            if local not in KNOWN_ELEMENTS:
                raise MalformedDescription(
                    f"mechkit:{local}", f"unknown element of the loop namespace; known: {KNOWN_ELEMENTS}"
                )
        elif "mechkit" in uri.lower():
            raise MalformedDescription(
                f"<{local}> in namespace {uri!r}", f"the loop namespace is {LOOP_NAMESPACE!r} (mistyped URI?)"
            )
        elif local.lower() in LOOP_LIKE:
            raise MalformedDescription(
                f"<{element.tag}>",
                f"a loop-like element outside the loop namespace "
                f"{LOOP_NAMESPACE!r}: declare loops as <mechkit:loop>, or as URDF+ "
                "<loop> with <predecessor> and <successor>",
            )


def parse_loops(urdf: str | ET.Element) -> list[LoopClosure]:
    """Read every `<mechkit:loop>` of a URDF (text or parsed root) into `LoopClosure` records, checked
    against its links and joints and against loop declarations that would be dropped (`check_loop_elements`).

    Args:
        urdf: URDF text or its parsed root.

    Returns:
        The loop closures, in document order.

    Raises:
        MalformedDescription: a malformed or misplaced loop declaration, a frame that is not a link, or two loops
            of one name.
    """
    root = parse_xml(urdf) if isinstance(urdf, str) else urdf
    check_loop_elements(root)
    frames = frame_names(root)
    loops = []
    for element in root.findall(f"{{{LOOP_NAMESPACE}}}loop"):
        loops.append(_parse_loop(element, frames))
    names = [loop.name for loop in loops]
    if len(set(names)) != len(names):
        raise MalformedDescription("mechkit:loop", f"duplicate loop names in {names}")
    return loops


def frame_names(root: ET.Element) -> dict[str, str | None]:
    """Every name a loop may use as a frame -> None, or why it is ambiguous.

    A link and a joint each give Pinocchio a frame of their name; one name for a joint and a link that
    is not that joint's child names two frames at different places.

    Args:
        root: the URDF's `<robot>` element.

    Returns:
        Name -> None (one frame), or the reason it names two.
    """
    out: dict[str, str | None] = {link.get("name"): None for link in root.findall("link")}
    for joint in root.findall("joint"):
        name, child = joint.get("name"), joint.find("child")
        if name in out and (child is None or child.get("link") != name):
            out[name] = "names both a link and a joint (not that joint's child): two frames"
        else:
            out.setdefault(name, None)
    return out


def _parse_loop(element: ET.Element, frame_ok: dict[str, str | None]) -> LoopClosure:
    name = element.get("name")
    where = f"mechkit:loop {name!r}"
    if not name:
        raise MalformedDescription("mechkit:loop", "missing attribute 'name'")
    kind = element.get("type")
    if kind not in LOOP_KINDS:
        raise MalformedDescription(where, f"type {kind!r} is not one of {LOOP_KINDS}")
    rows = element.get("rows", "spatial")
    if rows not in ROW_SETS:
        raise MalformedDescription(where, f"rows {rows!r} is not one of {ROW_SETS}")
    frames = {}
    for attr in ("frame_a", "frame_b"):
        frame = element.get(attr)
        if not frame:
            raise MalformedDescription(where, f"missing attribute {attr!r}")
        if frame not in frame_ok:
            raise MalformedDescription(where, f"{attr} {frame!r} is not a link or a joint of the URDF")
        if frame_ok[frame]:
            raise MalformedDescription(where, f"{attr} {frame!r} {frame_ok[frame]}")
        frames[attr] = frame
    if frames["frame_a"] == frames["frame_b"]:
        raise MalformedDescription(where, "frame_a and frame_b are the same link or joint")
    axis = _vector(element, "axis", where, required=kind in ("revolute", "prismatic") or rows != "spatial")
    axis_a = _vector(element, "axis_a", where, required=kind == "hooke")
    axis_b = _vector(element, "axis_b", where, required=kind == "hooke")
    if kind == "hooke" and rows == "planar":
        raise MalformedDescription(where, "a Hooke cut has no planar rows")
    if kind == "spherical" and rows == "spherical":
        raise MalformedDescription(where, "a spherical cut about a common centre has no rows left")
    return LoopClosure(
        name, kind, frames["frame_a"], frames["frame_b"], axis, axis_a, axis_b, rows, element.get("rows") is not None
    )


def parse_springs(urdf: str | ET.Element) -> tuple[JointSpring, ...]:
    """The `<mechkit:spring joint stiffness preload reference damping/>` elements as joint springs:
    effort = preload - stiffness (x - reference) - damping dx/dt (N m or N; stiffness N m/rad or N/m,
    reference rad or m, damping N m s/rad or N s/m; preload and damping default to 0).

    Args:
        urdf: URDF text or its parsed root.

    Returns:
        The springs, in document order.

    Raises:
        MalformedDescription: a spring without its joint, stiffness or reference, or with a value that
            is not a finite number (a negative stiffness or damping included).
    """
    out = []
    for element in (parse_xml(urdf) if isinstance(urdf, str) else urdf).iter(f"{{{LOOP_NAMESPACE}}}spring"):
        joint = element.get("joint")
        where = f"mechkit:spring {joint!r}"
        try:
            values = {
                a: float(element.attrib[a]) if a in ("stiffness", "reference") else float(element.get(a, "0"))
                for a in ("stiffness", "reference", "preload", "damping")
            }
        except (KeyError, ValueError) as err:
            raise MalformedDescription(where, f"bad or missing attribute {err}") from None
        if not joint or not all(np.isfinite(list(values.values()))) or values["stiffness"] < 0 or values["damping"] < 0:
            raise MalformedDescription(where, f"needs a joint and finite values, stiffness and damping >= 0: {values}")
        out.append(JointSpring(joint, **values))
    return tuple(out)


def parse_home(urdf: str | ET.Element, tag: str = "home") -> dict[str, float]:
    """The `<mechkit:home joint="..." value="..."/>` inputs of the default assembly (rad or m), or with
    `tag="guess"` the `<mechkit:guess>` values near which it is sought (they pick its branch).

    Args:
        urdf: URDF text or its parsed root.
        tag: "home" or "guess".

    Returns:
        Joint -> value (rad or m).

    Raises:
        MalformedDescription: a value that is not a finite number, or no joint name.
    """
    out = {}
    for element in (parse_xml(urdf) if isinstance(urdf, str) else urdf).findall(f"{{{LOOP_NAMESPACE}}}{tag}"):
        joint, text = element.get("joint"), element.get("value")
        try:
            value = float(text)
        except (TypeError, ValueError):
            raise MalformedDescription(f"mechkit:{tag} {joint!r}", f"value {text!r} is not a number") from None
        if not joint or not np.isfinite(value):
            raise MalformedDescription(f"mechkit:{tag} {joint!r}", "needs a joint name and a finite value")
        out[joint] = value
    return out


def _vector(element: ET.Element, attr: str, where: str, required: bool) -> np.ndarray | None:
    text = element.get(attr)
    if text is None:
        if required:
            raise MalformedDescription(where, f"missing attribute {attr!r}")
        return None
    try:
        vec = np.array([float(x) for x in text.split()])
    except ValueError:
        raise MalformedDescription(where, f"{attr}={text!r} is not three numbers") from None
    if vec.shape != (3,) or not np.all(np.isfinite(vec)) or not np.any(vec):
        raise MalformedDescription(where, f"{attr}={text!r} is not a non-zero, finite 3-vector")
    vec = vec / np.max(np.abs(vec))  # scaled first: the norm of 1e300 components would overflow
    return vec / np.linalg.norm(vec)


def build_model(urdf: str, root: pin.JointModel | None = None) -> pin.Model:
    """Pinocchio model of the URDF tree.

    Args:
        urdf: the URDF text.
        root: a joint the tree hangs from, named "root_joint" (e.g. a free-flyer), or None (fixed).

    Returns:
        The model (urdfdom's output on stderr captured, not shown).

    Raises:
        MalformedDescription: Pinocchio could not build it, or urdfdom complained.
    """
    with tempfile.TemporaryFile(mode="w+b") as captured:
        saved = os.dup(2)
        os.dup2(captured.fileno(), 2)
        try:
            model = pin.buildModelFromXML(urdf) if root is None else pin.buildModelFromXML(urdf, root)
        except (RuntimeError, ValueError) as err:
            raise MalformedDescription("urdf", f"Pinocchio could not build it: {err}") from None
        finally:
            os.dup2(saved, 2)
            os.close(saved)
        captured.seek(0)
        complaints = captured.read().decode(errors="replace").strip()
    if complaints:
        raise MalformedDescription("urdf", f"urdfdom: {complaints.splitlines()[0]}")
    return model
