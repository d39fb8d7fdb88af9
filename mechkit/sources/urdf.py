"""A `.urdf` file with `<mechkit:loop>` elements; its actuators are its `<transmission>` elements."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from mechkit.description import parse_home, parse_loops, parse_xml
from mechkit.exceptions import MalformedDescription
from mechkit.sources.checks import check_inertias, check_tree
from mechkit.sources.description import Description, read_text


def read_urdf(path: Path) -> Description:
    """The description in a URDF file (see `describe_urdf`)."""
    return describe_urdf(read_text(path), path, "urdf")


def describe_urdf(urdf: str, source: Path | None, fmt: str, params: dict[str, str] | None = None) -> Description:
    """Check a URDF text (tree, inertias, loop elements, home) and read its actuators.

    Raises:
        MalformedDescription: see `mechkit.sources.checks`, `mechkit.description.parse_loops`.
    """
    where = str(source) if source is not None else "urdf"
    root = parse_xml(urdf, where)
    check_tree(root)
    check_inertias(root)
    closures = tuple(parse_loops(root))
    joints = {j.get("name") for j in root.findall("joint") if j.get("type") != "fixed"}
    home = parse_home(root)
    for joint in home:
        if joint not in joints:
            raise MalformedDescription(f"mechkit:home {joint!r}", "not a moving joint of the URDF")
    name = root.get("name") or (source.name.split(".")[0] if source else "urdf")
    return Description(name, urdf, transmissions(root, joints), home, {}, source, fmt, dict(params or {}), closures)


def transmissions(root: ET.Element, joints: set[str]) -> tuple[str, ...]:
    """Joints driven by `<transmission>` elements (ROS format: `<transmission><joint name=.../>`)."""
    out: list[str] = []
    for transmission in root.findall("transmission"):
        for joint in transmission.findall("joint"):
            name = joint.get("name")
            if name not in joints:
                raise MalformedDescription(f"transmission {transmission.get('name')!r}",
                                           f"joint {name!r} is not a moving joint of the URDF")
            if name not in out:
                out.append(name)
    return tuple(out)
