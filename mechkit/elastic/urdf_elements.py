"""The elastic elements of a URDF (mechkit namespace): read into `ElasticData`, written back.

    <mechkit:beam link="crank_link" E="7e10" G="2.6e10" A="1.131e-4" I1="4.637e-9" I2="4.637e-9"
                  J="9.274e-9" axis1="0 -1 0" density="2700"/>
    <mechkit:elastic_joint joint="r11" centre="0.12" stiffness="1e8 1e8 1e8 1e5 1e5 1e5" drive="2e4"/>

`beam`: the section of a link's beams (`Section`; axis1 in the link's frame; density optional).
`elastic_joint`: a joint's centre along its axis (m), its diagonal stiffness in its frame, its drive
stiffness (`JointElasticity`; every attribute optional). The rigid pipeline ignores both elements.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np

from mechkit.base.exceptions import InvalidParameters, MalformedDescription
from mechkit.elastic.sections import ElasticData, JointElasticity, Section
from mechkit.sources.urdf import LOOP_NAMESPACE, parse_xml

BEAM = f"{{{LOOP_NAMESPACE}}}beam"
ELASTIC_JOINT = f"{{{LOOP_NAMESPACE}}}elastic_joint"
SECTION_ATTRIBUTES = ("E", "G", "A", "I1", "I2", "J")


def _numbers(element: ET.Element, attr: str, where: str, size: int) -> np.ndarray:
    text = element.get(attr, "")
    try:
        values = np.array([float(x) for x in text.split()])
    except ValueError:
        raise MalformedDescription(where, f"{attr}={text!r} is not {size} numbers") from None
    if values.shape != (size,):
        raise MalformedDescription(where, f"{attr}={text!r} is not {size} numbers")
    return values


def parse_elastic(urdf: str | ET.Element) -> ElasticData:
    """The `<mechkit:beam>` and `<mechkit:elastic_joint>` elements of a URDF.

    Args:
        urdf: the URDF text or its parsed root element.

    Returns:
        The `ElasticData` (empty where the URDF has no such element).

    Raises:
        MalformedDescription: a missing or bad attribute, a link or joint named twice or not in the URDF.
    """
    root = parse_xml(urdf) if isinstance(urdf, str) else urdf
    links = {link.get("name") for link in root.findall("link")}
    joints = {j.get("name") for j in root.findall("joint") if j.get("type") != "fixed"}
    joints |= {loop.get("name") for loop in root.findall(f"{{{LOOP_NAMESPACE}}}loop")}
    data = ElasticData()
    for element in root.iter(BEAM):
        link = element.get("link")
        where = f"mechkit:beam {link!r}"
        if link not in links:
            raise MalformedDescription(where, "not a link of the URDF")
        if link in data.sections:
            raise MalformedDescription(where, "a link has one section")
        try:
            values = {a: float(element.attrib[a]) for a in SECTION_ATTRIBUTES}
            density = float(element.get("density", "0"))
        except (KeyError, ValueError) as err:
            raise MalformedDescription(where, f"bad or missing attribute {err}") from None
        axis = _numbers(element, "axis1", where, 3) if element.get("axis1") is not None else np.array([0.0, 0.0, 1.0])
        try:
            data = data.with_section(link, Section(**values, axis1=axis, density=density))
        except InvalidParameters as err:
            raise MalformedDescription(where, str(err)) from None
    for element in root.iter(ELASTIC_JOINT):
        joint = element.get("joint")
        where = f"mechkit:elastic_joint {joint!r}"
        if joint not in joints:
            raise MalformedDescription(where, "not a moving joint or loop of the URDF")
        if joint in data.joints:
            raise MalformedDescription(where, "a joint has one elastic_joint element")
        try:
            centre = float(element.get("centre", "0"))
            drive = float(element.attrib["drive"]) if "drive" in element.attrib else None
            stiffness = _numbers(element, "stiffness", where, 6) if "stiffness" in element.attrib else None
            data = data.with_joint(joint, JointElasticity(centre, stiffness, drive))
        except (ValueError, InvalidParameters) as err:
            raise MalformedDescription(where, str(err)) from None
    return data


def _text(values: np.ndarray) -> str:
    return " ".join(repr(float(x)) for x in values)


def with_elastic(urdf: str, data: ElasticData) -> str:
    """The URDF text with its elastic elements replaced by `data`'s (the rest of the file unchanged).

    Args:
        urdf: the URDF text.
        data: the elastic data to write.

    Returns:
        The new URDF text.

    Raises:
        MalformedDescription: `data` names a link or joint the URDF lacks (read back by `parse_elastic`).
    """
    ET.register_namespace("mechkit", LOOP_NAMESPACE)
    root = parse_xml(urdf)
    for element in [e for e in root if e.tag in (BEAM, ELASTIC_JOINT)]:
        root.remove(element)
    for link, s in data.sections.items():
        attrs = {"link": link, **{a: repr(float(getattr(s, a))) for a in SECTION_ATTRIBUTES}, "axis1": _text(s.axis1)}
        if s.density:
            attrs["density"] = repr(float(s.density))
        ET.SubElement(root, BEAM, attrs)
    for joint, j in data.joints.items():
        attrs = {"joint": joint, "centre": repr(float(j.centre))}
        if j.stiffness is not None:
            attrs["stiffness"] = _text(j.stiffness)
        if j.drive is not None:
            attrs["drive"] = repr(float(j.drive))
        ET.SubElement(root, ELASTIC_JOINT, attrs)
    text = ET.tostring(root, encoding="unicode")
    parse_elastic(text)
    return text
