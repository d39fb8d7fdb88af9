"""`mechkit.sources.sdf_frames`: poses resolved through `relative_to` and `attached_to` agree with the
placements composed by hand, both SDFormat conventions (before and from 1.7) place joints and axes as
the specification says, and broken frame graphs are refused by name."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import pytest

from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.sdf_frames import MODEL, SdfFrames, number, numbers, sdf_version


def _frames(body: str, version: str = "1.7") -> SdfFrames:
    root = ET.fromstring(f'<sdf version="{version}"><model name="m">{body}</model></sdf>')
    return SdfFrames(root.find("model"), sdf_version(root, "test"), ())


def _se3(xyz, rpy) -> pin.SE3:
    return pin.SE3(pin.rpy.rpyToMatrix(*rpy), np.array(xyz, dtype=float))


def test_relative_to_chains_compose_as_placements():
    frames = _frames("""
        <link name="a"><pose>1 0 0 0 0 0.5</pose></link>
        <link name="b"><pose relative_to="a">0 2 0 0.3 0 0</pose></link>
        <frame name="f" attached_to="b"><pose relative_to="b">0 0 3 0 0.2 0</pose></frame>
        <joint name="j" type="revolute"><parent>a</parent><child>b</child><pose>0.1 0 0 0 0 0</pose>
          <axis><xyz expressed_in="a">1 0 0</xyz></axis></joint>""")
    a = _se3([1, 0, 0], [0, 0, 0.5])
    b = a * _se3([0, 2, 0], [0.3, 0, 0])
    assert frames.frame("b").isApprox(b, 1e-14)
    assert frames.frame("f").isApprox(b * _se3([0, 0, 3], [0, 0.2, 0]), 1e-14)
    joint = b * _se3([0.1, 0, 0], [0, 0, 0])  # a joint's pose defaults to its child's frame
    assert frames.frame("j").isApprox(joint, 1e-14)
    # the axis given in a's frame, returned in the joint's frame
    expected = joint.rotation.T @ a.rotation @ np.array([1.0, 0, 0])
    axis = frames.axis(frames.items["joint"]["j"], "axis", "test")
    assert np.allclose(axis, expected, atol=1e-14) and frames.frame(MODEL).isIdentity()
    assert frames.link_of("f", "frame", "test") == "b" and frames.link_of("j", "frame", "test") == "b"


def test_before_1_7_links_sit_in_the_model_frame_and_axes_may_use_it():
    frames = _frames(
        """
        <link name="a"><pose>0 0 1 0 0 0</pose></link>
        <link name="b"><pose>0 0 2 0 0 1.0</pose></link>
        <joint name="j" type="revolute"><parent>a</parent><child>b</child>
          <axis><xyz>1 0 0</xyz><use_parent_model_frame>true</use_parent_model_frame></axis></joint>""",
        "1.6",
    )
    assert frames.frame("j").isApprox(frames.frame("b"), 1e-14)
    axis = frames.axis(frames.items["joint"]["j"], "axis", "test")
    assert np.allclose(axis, [np.cos(1.0), -np.sin(1.0), 0.0], atol=1e-14)  # model x seen from b, turned by 1 rad


def test_quaternions_and_degrees():
    frames = _frames("""
        <link name="a"><pose rotation_format="quat_xyzw">0 0 0 0 0 0.7071067811865476 0.7071067811865476</pose></link>
        <link name="b"><pose degrees="true">0 0 0 0 0 90</pose></link>""")
    assert frames.frame("a").isApprox(frames.frame("b"), 1e-12)


@pytest.mark.parametrize(
    "word, in_degrees", [("true", 1), ("1", 1), ("True", 1), (" TRUE ", 1), ("false", 0), ("0", 0)]
)
def test_degrees_is_read_as_libsdformat_reads_a_boolean(word, in_degrees):
    """`degrees="1"` and `"True"` were read as radians (only the exact text "true" counted)."""
    frames = _frames(f'<link name="a"><pose degrees="{word}">0 0 0 0 0 90</pose></link>')
    angle = np.pi / 2 if in_degrees else 90.0
    assert frames.frame("a").isApprox(_se3([0, 0, 0], [0, 0, angle]), 1e-12)


@pytest.mark.parametrize(
    "body, why",
    [
        ('<link name="a"><pose degrees="yes">0 0 0 0 0 90</pose></link>', "degrees>='yes' is not a boolean"),
        ('<link name="a"><pose relative_to="b"/></link><link name="b"><pose relative_to="a"/></link>', "pose cycle"),
        ('<link name="a"><pose relative_to="nowhere"/></link>', "no such frame"),
        ('<link name="a"/><link name="a"/>', "repeated name"),
        ('<link name="a"><pose frame="b">0 0 0 0 0 0</pose></link>', "relative_to"),
    ],
)
def test_broken_frames_are_refused_by_name(body, why):
    with pytest.raises(MalformedDescription, match=why):
        _frames(body).frame("a")


def test_numbers_are_checked():
    element = ET.fromstring("<e><x>1 2 nan</x><y>4</y></e>")
    with pytest.raises(MalformedDescription, match="3 finite numbers"):
        numbers(element.find("x"), "test", 3, (0.0, 0.0, 0.0))
    assert number(element, "y", "test", None) == 4.0 and number(element, "z", "test", 2.5) == 2.5
    with pytest.raises(MalformedDescription, match="missing <z>"):
        number(element, "z", "test", None)
    with pytest.raises(MalformedDescription, match="version"):
        sdf_version(ET.fromstring('<sdf version="one"/>'), "test")
