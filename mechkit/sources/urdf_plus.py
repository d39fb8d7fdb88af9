"""URDF+ (Chignoli, Slotine, Wensing, Kim 2024, arXiv 2411.19753): loops and couplings inside the URDF,
as its urdfdom fork parses them (`urdf_parser/src/constraint.cpp`, `model.cpp`):

    <loop name="L" type="revolute|continuous|prismatic|fixed|planar">
      <predecessor link="A"><origin xyz="..." rpy="..."/></predecessor>   <!-- the loop frame on A -->
      <successor link="B"><origin xyz="..." rpy="..."/></successor>       <!-- the loop frame on B -->
      <axis xyz="1 0 0"/>                                                 <!-- in the loop frame -->
    </loop>
    <coupling name="C">
      <predecessor link="A"/><successor link="B"/>
      <ratio value="r"/>          <!-- successor velocity / predecessor velocity -->
    </coupling>

A loop is a cut joint whose frames (the link's frame moved by its `<origin>`, identity when absent)
coincide when closed, up to the joint's motion about (revolute, continuous) or along (prismatic) the
axis (default 1 0 0, as the fork's); a fixed loop welds them. (The authors' dynamics library,
generalized_rbda, closes every loop by the coincidence of the frames' origins alone; mechkit keeps the
declared joint.) A coupling ties the moving joints from the two links' nearest common ancestor: their
sum down to the successor = r x their sum down to the predecessor (rad or m; r defaults to 1), as
generalized_rbda builds it (for a rotor beside its link: x_rotor = r x_joint). Planar loops have no
cut kind in mechkit: refused by name.

The description's URDF is the tree with the loops as `<mechkit:loop>` elements: a loop frame that is
not its link's own frame is added as a massless link on a fixed joint (`<loop>_predecessor`,
`<loop>_successor`), so every URDF consumer sees it.
"""

from __future__ import annotations

import dataclasses
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from mechkit.base.exceptions import MalformedDescription, MethodUnavailable
from mechkit.core import Coupling
from mechkit.sources.description import Description, read_text
from mechkit.sources.urdf import LOOP_NAMESPACE, describe_urdf, parse_xml
from mechkit.sources.urdf_checks import check_tree, number

#: URDF+ loop types -> mechkit cut kinds.
LOOP_TYPES = {"revolute": "revolute", "continuous": "revolute", "prismatic": "prismatic", "fixed": "weld"}


def is_urdf_plus(root: ET.Element) -> bool:
    """Whether a URDF's root declares URDF+ constraints: a `<coupling>`, or a `<loop>` with a
    `<predecessor>` or `<successor>` (a bare `<loop frame_a=...>` is a mistyped `<mechkit:loop>`).

    Args:
        root: the URDF's `<robot>` element.

    Returns:
        Whether it is a URDF+ file.
    """
    return any(
        child.tag == "coupling"
        or (child.tag == "loop" and (child.find("predecessor") is not None or child.find("successor") is not None))
        for child in root
    )


def read_urdf_plus(path: Path) -> Description:
    """The mechanism of a URDF+ file: its tree, its loops as cuts, its couplings as coupling rows.

    Args:
        path: the URDF+ file.

    Returns:
        The description; `urdf` the tree with `<mechkit:loop>` elements (and added loop frames),
        `couplings` the URDF+ couplings after the tree's `<mimic>` rows.

    Raises:
        MalformedDescription: a malformed tree, or a loop or coupling naming a link the URDF lacks,
            missing a predecessor or successor, with an unknown type, a bad origin, axis or ratio,
            a repeated name, or coupling a link without a one-freedom parent joint.
        MethodUnavailable: a planar loop (mechkit has no planar cut).
    """
    root = parse_xml(read_text(path), str(path))
    check_tree(root)
    links = {link.get("name") for link in root.findall("link")}
    parent_joint = {j.find("child").get("link"): j for j in root.findall("joint")}
    taken = links | {j.get("name") for j in root.findall("joint")}
    seen: set[str] = set()
    loops, couplings = [], []
    for element in [e for e in root if e.tag in ("loop", "coupling")]:
        name = element.get("name")
        where = f"<{element.tag} name={name!r}>"
        if not name:
            raise MalformedDescription(f"<{element.tag}>", "missing attribute 'name'")
        if name in seen:
            raise MalformedDescription(where, "declared twice (URDF+ constraint names are unique)")
        seen.add(name)
        ends = [_end(element, tag, where, links) for tag in ("predecessor", "successor")]
        if ends[0][0] == ends[1][0]:
            raise MalformedDescription(where, f"predecessor and successor are the same link {ends[0][0]!r}")
        if element.tag == "coupling":
            couplings.append(_coupling(element, name, where, ends, parent_joint))
        else:
            loops += _loop(element, name, where, ends, taken)
        root.remove(element)
    root.extend(loops)
    ET.register_namespace("mechkit", LOOP_NAMESPACE)
    desc = describe_urdf(ET.tostring(root, encoding="unicode"), path, "urdf+")
    return dataclasses.replace(desc, couplings=desc.couplings + tuple(couplings))


def _end(element: ET.Element, tag: str, where: str, links: set[str]) -> tuple[str, ET.Element | None]:
    """(link, its <origin> or None) of a constraint's predecessor or successor."""
    end = element.find(tag)
    if end is None:
        misspelt = [e.tag for e in element if e.tag != tag and e.tag[:3] == tag[:3]]
        hint = f" (found <{misspelt[0]}>: URDF+ spells it <{tag} link=...>)" if misspelt else ""
        raise MalformedDescription(where, f"missing <{tag} link=...>{hint}")
    link = end.get("link")
    if link not in links:
        raise MalformedDescription(f"{where} <{tag}>", f"link={link!r} is not a link of the URDF")
    return link, end.find("origin")


def _loop(
    element: ET.Element, name: str, where: str, ends: list[tuple[str, ET.Element | None]], taken: set[str]
) -> list[ET.Element]:
    """The elements a URDF+ loop becomes: the links and fixed joints of its frames (where a frame is not
    its link's own) and its `<mechkit:loop>`."""
    kind = element.get("type")
    if kind == "planar":
        raise MethodUnavailable("URDF+ reader", f"{where} is a planar loop: mechkit has no planar cut kind")
    if kind not in LOOP_TYPES:
        raise MalformedDescription(where, f"type {kind!r} is not one of {(*LOOP_TYPES, 'planar')}")
    attrs, out = {"name": name, "type": LOOP_TYPES[kind]}, []
    for (link, origin), tag, attr in zip(ends, ("predecessor", "successor"), ("frame_a", "frame_b")):
        xyz, rpy = (_triple(origin, key, f"{where} <{tag}><origin>") for key in ("xyz", "rpy"))
        if not (np.any(xyz) or np.any(rpy)):
            attrs[attr] = link
            continue
        frame = f"{name}_{tag}"
        while frame in taken or f"{frame}_fixed" in taken:
            frame += "_"
        taken |= {frame, f"{frame}_fixed"}
        attrs[attr] = frame
        joint = ET.Element("joint", name=f"{frame}_fixed", type="fixed")
        ET.SubElement(joint, "parent", link=link)
        ET.SubElement(joint, "child", link=frame)
        ET.SubElement(
            joint, "origin", xyz=" ".join(repr(float(x)) for x in xyz), rpy=" ".join(repr(float(x)) for x in rpy)
        )
        out += [ET.Element("link", name=frame), joint]
    if kind != "fixed":
        vector = _triple(element.find("axis"), "xyz", f"{where} <axis>", default="1 0 0")
        if not np.any(vector):
            raise MalformedDescription(f"{where} <axis>", "xyz is a zero vector")
        vector = vector / np.max(np.abs(vector))  # scaled first: the norm of 1e300 components would overflow
        attrs["axis"] = " ".join(repr(float(x)) for x in vector / np.linalg.norm(vector))
    return out + [ET.Element(f"{{{LOOP_NAMESPACE}}}loop", attrs)]


def _coupling(
    element: ET.Element,
    name: str,
    where: str,
    ends: list[tuple[str, ET.Element | None]],
    parent_joint: dict[str, ET.Element],
) -> Coupling:
    """The coupling row of a URDF+ coupling: the sum of the moving joints from the links' nearest common
    ancestor to the successor = ratio x that sum to the predecessor (the fork's constraint, as its
    authors' dynamics library builds it)."""
    paths = []
    for link, _ in ends:  # each link's joints up to the root, nearest first
        path, at = [], link
        while at in parent_joint:
            path.append(parent_joint[at])
            at = parent_joint[at].find("parent").get("link")
        paths.append(path)
    common = {id(j) for j in paths[0]} & {id(j) for j in paths[1]}
    terms = []
    for path, (link, _), tag in zip(paths, ends, ("predecessor", "successor")):
        joints = [j for j in path if id(j) not in common and j.get("type") != "fixed"]
        for joint in joints:
            if joint.get("type") not in ("revolute", "continuous", "prismatic"):
                raise MalformedDescription(
                    f"{where} <{tag}>",
                    f"joint {joint.get('name')!r} on the way to {link!r} is "
                    f"{joint.get('type')}: a coupling sums one-freedom joints",
                )
        terms.append(tuple((j.get("name"), 1.0) for j in joints))
    if not terms[0] or not terms[1]:
        raise MalformedDescription(
            where, "a link has no moving joint below the links' nearest common ancestor: nothing to couple"
        )
    ratio = element.find("ratio")
    value = 1.0 if ratio is None else number(ratio.get("value"), f"{where} <ratio>", "value")
    return Coupling(name, terms[1], terms[0], (0.0, value))


def _triple(element: ET.Element | None, key: str, where: str, default: str = "0 0 0") -> np.ndarray:
    text = default if element is None else element.get(key, default)
    parts = text.split()
    if len(parts) != 3:
        raise MalformedDescription(where, f"{key}={text!r} is not three numbers")
    return np.array([number(p, where, key) for p in parts])
