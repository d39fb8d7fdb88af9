"""A URDF's `<mimic>` joints as coupling rows.

A joint's `<mimic joint="leader" multiplier="m" offset="o"/>` (defaults 1 and 0) is the coupling row
x_joint = m x_leader + o (rad or m); the tree keeps the mimic joint as an ordinary joint (Pinocchio's
`mimic=False`), so the row is what ties it. `mechkit.sources.urdf.describe_urdf` reads them.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

from mechkit.base.exceptions import MalformedDescription
from mechkit.core import Coupling
from mechkit.sources.urdf_checks import number


def parse_mimics(root: ET.Element) -> tuple[Coupling, ...]:
    """The `<mimic>` of every joint as a coupling row x_joint = multiplier x_leader + offset (rad or m).

    A mimic on a fixed joint couples nothing (no consumer moves a fixed joint): skipped. A mimic of a
    fixed joint follows its value, zero: the row fixes x_joint = offset.

    Args:
        root: the URDF's `<robot>` element.

    Returns:
        One coupling per mimic, in the URDF's joint order.

    Raises:
        MalformedDescription: a mimic of a joint the URDF lacks or of itself, on or of a joint of more
            than one freedom (floating, planar), a multiplier or offset that is not a finite number, or
            mimics that form a cycle.
    """
    types = {j.get("name"): j.get("type") for j in root.findall("joint")}
    leader_of: dict[str, str] = {}
    out = []
    for joint in root.findall("joint"):
        mimic = joint.find("mimic")
        name = joint.get("name")
        if mimic is None or types[name] == "fixed":
            continue
        leader, where = mimic.get("joint"), f"joint {name!r} <mimic>"
        if leader not in types:
            raise MalformedDescription(where, f"joint={leader!r} is not a joint of the URDF")
        if leader == name:
            raise MalformedDescription(where, "a joint cannot mimic itself")
        for joint_name in (name, leader):
            if types[joint_name] in ("floating", "planar"):
                raise MalformedDescription(
                    where, f"joint {joint_name!r} is {types[joint_name]}: a mimic couples one-freedom joints"
                )
        multiplier, offset = (
            number(mimic.get(k, default), where, k) for k, default in (("multiplier", "1"), ("offset", "0"))
        )
        if types[leader] == "fixed":
            out.append(Coupling(name, ((name, 1.0),), (), (offset,)))
            continue
        leader_of[name] = leader
        out.append(Coupling(name, ((name, 1.0),), ((leader, 1.0),), (offset, multiplier)))
    for start, first in leader_of.items():
        chain, joint = [start], first
        while joint in leader_of and joint not in chain:
            chain.append(joint)
            joint = leader_of[joint]
        if joint in chain:
            cycle = chain[chain.index(joint) :] + [joint]
            raise MalformedDescription(f"joint {joint!r} <mimic>", f"the mimics form a cycle {' -> '.join(cycle)}")
    return tuple(out)
