"""URDF+ export (Chignoli, Slotine, Wensing, Kim 2024; read back by `mechkit.sources.urdf_plus`): the tree
URDF with its loops and couplings as URDF+ elements.

| mechkit | URDF+ |
|---|---|
| revolute / prismatic / weld cut | `<loop type="revolute" / "prismatic" / "fixed">` |
| spherical, Hooke cut | none exists: `MethodUnavailable` |
| a mimic's row (named after its joint: x_f = m x_l + o) | the follower joint's `<mimic joint multiplier offset>` |
| a linear row without offset over the joints below two links' nearest common ancestor | `<coupling>`, `<ratio>` |
| another row of one joint to another, linear | the follower joint's `<mimic>` (the row then takes the joint's name) |
| actuated joint | `<transmission>`, and `<mechkit:home joint value>` (the home inputs) |

A `<loop>` has frame_a's link as predecessor, frame_b's as successor and its `<axis>` in frame_a's frame; a
`<coupling>` is of those two links; `<mimic>` is URDF's own. The home inputs make `mechkit.load` assemble the
same default configuration, on the branch nearest its guess. A cut frame is a URDF link (or a joint: its child
link's frame). The URDF keeps mechkit's other elements (`<mechkit:spring>`); its `<mechkit:loop>`,
`<mechkit:home>`, `<mimic>` and `<transmission>` elements are written anew. A tree with joints URDF lacks
(ball, free-flyer: no URDF text) and tendon actuators have no URDF+ counterpart.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import TYPE_CHECKING

from mechkit.base.exceptions import MethodUnavailable
from mechkit.export.urdf import source_text
from mechkit.export.xmltext import numbers as _fmt
from mechkit.sources.urdf import LOOP_NAMESPACE

if TYPE_CHECKING:
    from mechkit.core import Coupling, LoopClosure
    from mechkit.mechanism import Mechanism

#: mechkit cut kinds -> URDF+ loop types.
LOOP_TYPES = {"revolute": "revolute", "prismatic": "prismatic", "weld": "fixed"}
_WRITTEN_AGAIN = ("loop", "home")


def to_urdf_plus(mech: Mechanism) -> str:
    """URDF+ text of the mechanism (see the module).

    Args:
        mech: the mechanism.

    Returns:
        The URDF+ document (its tree, `<loop>` and `<coupling>` elements, home and actuators).

    Raises:
        MethodUnavailable: no URDF tree (ball or free joints: `mechkit.export.urdf`), a spherical or Hooke
            cut, a cut frame that is not a URDF link or joint, a coupling neither a mimic nor a URDF+ coupling
            can write, a tendon actuator.
    """
    tendons = [a.name for a in mech.closure_model.actuators]
    if tendons:
        raise MethodUnavailable("urdf+ export", f"actuator {tendons[0]!r} drives a tendon: URDF+ drives joints")
    robot = ET.fromstring(source_text(mech, "urdf+ export", writes_couplings=True))
    for element in list(robot):
        if element.tag == "transmission" or element.tag in {f"{{{LOOP_NAMESPACE}}}{t}" for t in _WRITTEN_AGAIN}:
            robot.remove(element)
    joints = {j.get("name"): j for j in robot.findall("joint")}
    links = {link.get("name") for link in robot.findall("link")}
    for joint in joints.values():
        for mimic in joint.findall("mimic"):
            joint.remove(mimic)
    for closure in mech.closures:
        robot.append(_loop(closure, joints, links))
    for coupling in mech.closure_model.couplings:
        _coupling(coupling, robot, joints)
    for name in mech.actuated:
        transmission = ET.SubElement(robot, "transmission", name=f"{name}_transmission")
        ET.SubElement(transmission, "type").text = "transmission_interface/SimpleTransmission"
        ET.SubElement(
            ET.SubElement(transmission, "joint", name=name), "hardwareInterface"
        ).text = "hardware_interface/EffortJointInterface"
        ET.SubElement(
            robot, f"{{{LOOP_NAMESPACE}}}home", joint=name, value=repr(float(mech.home_q[mech.q_index(name)]))
        )
    ET.register_namespace("mechkit", LOOP_NAMESPACE)
    ET.indent(robot)
    return '<?xml version="1.0" ?>\n' + ET.tostring(robot, encoding="unicode") + "\n"


def _link_of(frame: str, joints: dict[str, ET.Element], links: set[str], cut: str) -> str:
    """The URDF link whose frame is `frame` (a link, or a joint: its child link)."""
    if frame in links:
        return frame
    if frame in joints:
        return joints[frame].find("child").get("link")
    raise MethodUnavailable("urdf+ export", f"cut {cut!r}: frame {frame!r} is neither a link nor a joint of the URDF")


def _loop(closure: LoopClosure, joints: dict[str, ET.Element], links: set[str]) -> ET.Element:
    if closure.kind not in LOOP_TYPES:
        raise MethodUnavailable(
            "urdf+ export",
            f"cut {closure.name!r} is {closure.kind}: URDF+ loops are revolute, prismatic, fixed or planar",
        )
    loop = ET.Element("loop", name=closure.name, type=LOOP_TYPES[closure.kind])
    ET.SubElement(loop, "predecessor", link=_link_of(closure.frame_a, joints, links, closure.name))
    ET.SubElement(loop, "successor", link=_link_of(closure.frame_b, joints, links, closure.name))
    if closure.axis is not None:
        ET.SubElement(loop, "axis", xyz=_fmt(closure.axis))
    return loop


def _path(link: str, joints: dict[str, ET.Element]) -> list[str]:
    """The joints from the root down to `link`, nearest last."""
    parent = {j.find("child").get("link"): name for name, j in joints.items()}
    out = []
    while link in parent:
        out.append(parent[link])
        link = joints[parent[link]].find("parent").get("link")
    return out[::-1]


def _deepest(end: tuple[tuple[str, float], ...], joints: dict[str, ET.Element]) -> str:
    """The child link of the joint of `end` deepest in the tree."""
    return max((joints[j].find("child").get("link") for j, _ in end), key=lambda link: len(_path(link, joints)))


def _coupling(coupling: Coupling, robot: ET.Element, joints: dict[str, ET.Element]) -> None:
    """Write a coupling row as a mimic, or a URDF+ `<coupling>`, in the order of the module's table."""
    poly = tuple(coupling.polynomial) + (0.0,) * (2 - len(coupling.polynomial))
    linear = len(coupling.polynomial) <= 2 and coupling.follower_ref == 0.0 and coupling.leader_ref == 0.0
    follower, leader = coupling.follower, coupling.leader
    mimic = linear and len(follower) == len(leader) == 1 and follower[0][1] == leader[0][1] == 1.0
    if mimic and coupling.name == follower[0][0]:  # a mimic's row is named after its joint
        ET.SubElement(
            joints[follower[0][0]],
            "mimic",
            joint=leader[0][0],
            multiplier=repr(float(poly[1])),
            offset=repr(float(poly[0])),
        )
        return
    if linear and leader and poly[0] == 0.0 and all(c == 1.0 for _, c in follower + leader):
        succ, pred = _deepest(follower, joints), _deepest(leader, joints)
        paths = [set(_path(link, joints)) for link in (succ, pred)]
        moving = [{j for j in p - (paths[0] & paths[1]) if joints[j].get("type") != "fixed"} for p in paths]
        if moving == [{j for j, _ in follower}, {j for j, _ in leader}]:
            element = ET.SubElement(robot, "coupling", name=coupling.name)
            ET.SubElement(element, "predecessor", link=pred)
            ET.SubElement(element, "successor", link=succ)
            ET.SubElement(element, "ratio", value=repr(float(poly[1])))
            return
    if mimic:
        ET.SubElement(
            joints[follower[0][0]],
            "mimic",
            joint=leader[0][0],
            multiplier=repr(float(poly[1])),
            offset=repr(float(poly[0])),
        )
        return
    raise MethodUnavailable(
        "urdf+ export",
        f"coupling {coupling.name!r} is neither a mimic (one joint, linear) nor a "
        "URDF+ coupling (linear, no offset, the sums of the joints below two links' nearest common "
        "ancestor)",
    )
