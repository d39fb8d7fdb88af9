"""Checks of a URDF tree that urdfdom lets through or reports only on stderr: its shape and its inertias
(what is physically invalid; massless links are valid).

Every failure is a `MalformedDescription` naming the element; nothing is built from a bad file.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np

from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.physical import check_body


def check_tree(root: ET.Element) -> None:
    """Links and joints form one tree: unique names, known parents and children, one root, no cycle.

    Args:
        root: the URDF's <robot> element.

    Raises:
        MalformedDescription: the first fault found, naming the link or joint.
    """
    if root.tag != "robot":
        raise MalformedDescription(f"<{root.tag}>", "the root element of a URDF must be <robot>")
    links = [link.get("name") for link in root.findall("link")]
    if not links:
        raise MalformedDescription("urdf", "no <link>: nothing to build")
    _unique(links, "link")
    joints = root.findall("joint")
    _unique([j.get("name") for j in joints], "joint")
    parent_of: dict[str, str] = {}
    children: dict[str, list[str]] = {}
    for joint in joints:
        name = joint.get("name")
        ends = []
        for tag in ("parent", "child"):
            element = joint.find(tag)
            link = None if element is None else element.get("link")
            if link not in links:
                raise MalformedDescription(f"joint {name!r}", f"{tag} link {link!r} is not a link of the URDF")
            ends.append(link)
        parent, child = ends
        if child in parent_of:
            raise MalformedDescription(
                f"link {child!r}",
                f"has two parent joints ({parent_of[child]!r}, {name!r}): "
                "a tree has one; close the loop with a <mechkit:loop> instead",
            )
        parent_of[child] = name
        children.setdefault(parent, []).append(child)
    roots = [link for link in links if link not in parent_of]
    if not roots:
        raise MalformedDescription("urdf", "the joints form a cycle: every link has a parent joint")
    if len(roots) > 1:
        raise MalformedDescription("urdf", f"several root links {roots}: the links are not one tree")
    reached, stack = set(), [roots[0]]
    while stack:
        link = stack.pop()
        reached.add(link)
        stack.extend(children.get(link, []))
    lost = [link for link in links if link not in reached]
    if lost:
        raise MalformedDescription(f"link {lost[0]!r}", "is on a cycle of joints, not on the tree from the root")


def _unique(names: list[str | None], what: str) -> None:
    if any(not n for n in names):
        raise MalformedDescription(f"<{what}>", "missing attribute 'name'")
    seen = set()
    for n in names:
        if n in seen:
            raise MalformedDescription(f"{what} {n!r}", "declared twice")
        seen.add(n)


def check_inertias(root: ET.Element) -> None:
    """Every `<inertial>` is physically possible: a finite mass that is not negative (kg) and an inertia
    about the centre of mass (kg m^2) whose principal moments are not negative (positive semi-definite)
    and satisfy the triangle inequality (each at most the sum of the other two).

    Zero is valid: a massless link (all zero) is a frame, a point mass has a zero inertia, a thin rod a
    zero principal moment, and a mass of zero with a non-zero inertia is a rotor whose mass the file
    counts elsewhere (URDF+ files write motor rotors so: it adds rotational inertia, no weight).
    Moments are judged as `mechkit.sources.physical.check_body` judges every format's bodies.

    Args:
        root: the URDF's <robot> element.

    Raises:
        MalformedDescription: naming the link and the value.
    """
    for link in root.findall("link"):
        inertial = link.find("inertial")
        if inertial is None:
            continue
        where = f"link {link.get('name')!r}"
        mass = inertial.find("mass")
        text = None if mass is None else mass.get("value")
        value = number(text, where, "mass")
        element = inertial.find("inertia")
        c = {
            k: number(element.get(k, "0") if element is not None else "0", where, k)
            for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
        }
        matrix = np.array(
            [[c["ixx"], c["ixy"], c["ixz"]], [c["ixy"], c["iyy"], c["iyz"]], [c["ixz"], c["iyz"], c["izz"]]]
        )
        check_body(where, value, matrix, c)


def number(text: str | None, where: str, what: str) -> float:
    """A finite number from an attribute's text.

    Args:
        text: the attribute's text (None: absent).
        where: the element, named in the error.
        what: the attribute, named in the error.

    Returns:
        The number.

    Raises:
        MalformedDescription: absent, not a number, or not finite.
    """
    try:
        value = float(text)
    except (TypeError, ValueError):
        raise MalformedDescription(where, f"{what} {text!r} is not a number") from None
    if not np.isfinite(value):
        raise MalformedDescription(where, f"{what} {text!r} is not finite")
    return value
