"""mechkit's own URDF of any mechanism: what `mechkit urdf` and `export --format urdf` write.

Where the mechanism's URDF text is its whole description (a registered mechanism, a URDF or xacro file) that
text is written, with a `<transmission>` for each actuator and a `<mechkit:home>` for each home input it does
not declare (the registry's actuators live in the spec, not in the template). Otherwise (a mechanism read from
SDFormat or MJCF, or reduced by `--lock` / `--keep` / `--fix`) the file is generated from the model and its
records: the tree with its joint limits, `<mechkit:loop>`s (with their rows where they were chosen), one
`<mimic>` per coupling, a `<transmission>` per actuator, `<mechkit:spring>`s, `<mechkit:home>`s and
`<mechkit:guess>`es (the home values of the other joints, which pick the same assembly branch); the
beams, elastic joints and visuals of the URDF it was reduced from are carried to the links and joints that
remain. What URDF cannot say is refused by name, never dropped: a ball, universal or free joint in the tree,
a coupling that is not one joint following another linearly, an actuator driving several joints.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MethodUnavailable
from mechkit.core import Coupling
from mechkit.export.xmltext import numbers
from mechkit.sources.pinocchio_tree import tree_urdf
from mechkit.sources.urdf import LOOP_NAMESPACE, parse_loops, parse_springs, parse_xml
from mechkit.sources.urdf_mimics import parse_mimics

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

ET.register_namespace("mechkit", LOOP_NAMESPACE)

#: The elements of the loop namespace a reduced mechanism's source URDF lends the written file, and the
#: attribute naming what each applies to (a link or a joint).
CARRIED = {"beam": "link", "elastic_joint": "joint"}


def to_urdf(mech: Mechanism) -> str:
    """The mechanism as mechkit's URDF (see the module docstring).

    Args:
        mech: the mechanism.

    Returns:
        The URDF text.

    Raises:
        MethodUnavailable: what URDF cannot say (named): a joint of several freedoms in the tree, a coupling
            that is not a mimic, an actuator of several joints.
    """
    _check_actuators(mech)
    if mech.urdf is not None and _describes(mech, parse_xml(mech.urdf)):
        extra = _actuation(mech, parse_xml(mech.urdf))  # the text kept byte for byte, the declarations added
        if not extra:
            return mech.urdf
        for element in extra:
            ET.indent(element, "  ", level=1)
        declared = f' xmlns:mechkit="{LOOP_NAMESPACE}"'  # the robot element declares it
        added = "".join(f"  {ET.tostring(e, encoding='unicode').replace(declared, '')}\n" for e in extra)
        end = mech.urdf.rindex("</robot>")
        return mech.urdf[:end] + added + mech.urdf[end:]
    root = _generated(mech)
    root.extend(_actuation(mech, root))
    ET.indent(root, "  ")
    return '<?xml version="1.0" ?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def source_text(mech: Mechanism, writer: str, writes_couplings: bool = False) -> str:
    """The URDF text another writer starts from: the mechanism's own where it describes the whole mechanism,
    else `to_urdf`'s (a reduced mechanism, or one read from SDFormat or MJCF whose tree text lacks its
    couplings, springs and actuators).

    Args:
        mech: the mechanism.
        writer: the writer's name, for a refusal (e.g. "urdf+ export").
        writes_couplings: the writer writes the couplings itself (URDF+): a text without them as mimics will do.

    Returns:
        The URDF text.

    Raises:
        MethodUnavailable: see `to_urdf`, named for `writer`.
    """
    if mech.urdf is not None and _describes(mech, parse_xml(mech.urdf), writes_couplings):
        return mech.urdf
    try:
        return to_urdf(mech)
    except MethodUnavailable as err:
        raise MethodUnavailable(writer, err.why) from None


def _describes(mech: Mechanism, root: ET.Element, without_couplings: bool = False) -> bool:
    """Whether the URDF text holds the mechanism's tree and records (its loops, couplings and springs; the
    couplings not asked `without_couplings`)."""
    joints = {j.get("name") for j in root.findall("joint") if j.get("type") != "fixed"}
    return (
        joints == set(mech.model.names[1:])
        and {c.name for c in parse_loops(root)} == {c.name for c in mech.closures}
        and (without_couplings or len(parse_mimics(root)) == len(mech.closure_model.couplings))
        and len(parse_springs(root)) == len(mech.springs.springs)
    )


def _generated(mech: Mechanism) -> ET.Element:
    """The URDF generated from the model and the records."""
    model = mech.model
    text = tree_urdf(model, tuple(mech.closures))
    if text is None:
        joint = next(
            model.names[j]
            for j in range(1, model.njoints)
            if model.joints[j].shortname() not in _ONE_FREEDOM
            and not (model.joints[j].shortname() == "JointModelFreeFlyer" and model.parents[j] == 0)
        )
        raise MethodUnavailable(
            "urdf export",
            f"joint {joint!r} is a {model.joints[model.getJointId(joint)].shortname()}: URDF has no such joint "
            "(export --format mjcf keeps it)",
        )
    root = parse_xml(text)
    joints = {j.get("name"): j for j in root.findall("joint")}
    for j in range(1, model.njoints):
        limit = joints[model.names[j]].find("limit")
        if limit is not None:
            k = model.idx_qs[j]
            for attr, values in (
                ("lower", model.lowerPositionLimit),
                ("upper", model.upperPositionLimit),
                ("effort", model.effortLimit),
                ("velocity", model.velocityLimit),
            ):
                value = float(values[model.idx_vs[j] if attr in ("effort", "velocity") else k])
                if np.isfinite(value):
                    limit.set(attr, repr(value))
    for loop, closure in zip(root.iter(f"{{{LOOP_NAMESPACE}}}loop"), mech.closures):
        if closure.explicit_rows:
            loop.set("rows", closure.rows)
    add_mimics(mech, root, "urdf export")
    for spring in mech.springs.springs:
        ET.SubElement(
            root,
            f"{{{LOOP_NAMESPACE}}}spring",
            joint=spring.joint,
            stiffness=repr(float(spring.stiffness)),
            reference=repr(float(spring.reference)),
            preload=repr(float(spring.preload)),
            damping=repr(float(spring.damping)),
        )
    if mech.source_urdf is not None:
        _carry(parse_xml(mech.source_urdf), root, model)
    return root


#: Pinocchio joints URDF has a word for (`tree_urdf` writes them).
_ONE_FREEDOM = {
    *(f"JointModel{k}{a}" for k in ("R", "P") for a in "XYZ"),
    "JointModelRevoluteUnaligned",
    "JointModelPrismaticUnaligned",
}


def linear_coupling(coupling: Coupling, writer: str) -> tuple[str, str, float, float]:
    """A coupling as one joint following another linearly: x_f = multiplier x_l + offset (URDF's mimic, MJCF's
    joint equality of degree one); else refused.

    Args:
        coupling: the coupling.
        writer: the writer's name, for the refusal.

    Returns:
        (follower, leader, multiplier, offset).

    Raises:
        MethodUnavailable: several joints on a side, none leading, or a polynomial of degree two or more.
    """
    if len(coupling.follower) != 1 or len(coupling.leader) != 1 or len(coupling.polynomial) > 2:
        raise MethodUnavailable(
            writer,
            f"coupling {coupling.name!r} is not one joint following another linearly: the format cannot say it",
        )
    (follower, cf), (leader, cl) = coupling.follower[0], coupling.leader[0]
    c0, c1 = (tuple(coupling.polynomial) + (0.0,))[:2]
    return follower, leader, c1 * cl / cf, (coupling.follower_ref + c0 - c1 * coupling.leader_ref) / cf


def add_mimics(mech: Mechanism, root: ET.Element, writer: str) -> None:
    """A `<mimic>` on the follower joint of every coupling the URDF does not hold yet (`linear_coupling`).

    Args:
        mech: the mechanism.
        root: the URDF's robot element, changed in place.
        writer: the writer's name, for a refusal.

    Raises:
        MethodUnavailable: a coupling `linear_coupling` refuses, or a joint following two.
    """
    joints = {j.get("name"): j for j in root.findall("joint")}
    held = {c.follower[0][0] for c in parse_mimics(root)}
    for coupling in mech.closure_model.couplings:
        follower, leader, multiplier, offset = linear_coupling(coupling, writer)
        if follower in held:
            continue
        if joints[follower].find("mimic") is not None:
            raise MethodUnavailable(writer, f"joint {follower!r} follows two couplings: URDF has one mimic per joint")
        ET.SubElement(joints[follower], "mimic", joint=leader, multiplier=repr(multiplier), offset=repr(offset))


def _carry(source: ET.Element, root: ET.Element, model: pin.Model) -> None:
    """The source URDF's beams, elastic joints and visuals, for the links and joints that remain."""
    links = {link.get("name"): link for link in root.findall("link")}
    for tag, attr in CARRIED.items():
        for element in source.iter(f"{{{LOOP_NAMESPACE}}}{tag}"):
            name = element.get(attr)
            if (attr == "link" and name in links) or (attr == "joint" and model.existJointName(name)):
                root.append(element)
    for link in source.findall("link"):
        if link.get("name") in links:
            for visual in link.findall("visual"):
                links[link.get("name")].append(visual)


def _check_actuators(mech: Mechanism) -> None:
    """Refuse an actuator URDF's transmission cannot say: one that drives several joints."""
    for actuator in mech.closure_model.actuators:
        if len(actuator.joints) != 1 or actuator.joints[0][1] != 1.0:
            raise MethodUnavailable(
                "urdf export",
                f"actuator {actuator.name!r} drives {[j for j, _ in actuator.joints]}: a URDF transmission drives "
                "one joint (export --format mjcf keeps it)",
            )


def _actuation(mech: Mechanism, root: ET.Element) -> list[ET.Element]:
    """A `<transmission>` per actuator, a `<mechkit:home>` per home input and a `<mechkit:guess>` per other joint
    (at its home value: the assembly branch) that the URDF does not declare."""
    out = []
    driven = {j.get("name") for t in root.findall("transmission") for j in t.findall("joint")}
    for name in mech.actuated:
        joint = next((a.joints[0][0] for a in mech.closure_model.actuators if a.name == name), name)
        if joint not in driven:
            transmission = ET.Element("transmission", name=f"{joint}_transmission")
            ET.SubElement(transmission, "type").text = "transmission_interface/SimpleTransmission"
            element = ET.SubElement(transmission, "joint", name=joint)
            ET.SubElement(element, "hardwareInterface").text = "hardware_interface/EffortJointInterface"
            actuator = ET.SubElement(transmission, "actuator", name=f"{joint}_motor")
            ET.SubElement(actuator, "mechanicalReduction").text = "1"
            out.append(transmission)
    declared = {h.get("joint") for tag in ("home", "guess") for h in root.iter(f"{{{LOOP_NAMESPACE}}}{tag}")}
    model = mech.model
    for name, value in mech.joint_values(mech.home_q).items():
        one = model.existJointName(name) and model.joints[model.getJointId(name)].nq == 1
        if one and name not in declared:  # the inputs' values, and the others' to pick the same branch
            tag = "home" if name in mech.actuated else "guess"
            out.append(ET.Element(f"{{{LOOP_NAMESPACE}}}{tag}", joint=name, value=numbers(value)))
    return out
