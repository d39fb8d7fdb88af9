"""`mechkit.sources.drake_elements`: Drake's ball constraint and Gazebo's joint close the four-bar as
`<mechkit:loop>` does (one freedom, one cut), with their frames where the files put them."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from tests_support import FIXTURES

import mechkit
from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.drake_elements import read_tool_closures

CLOSURES = FIXTURES / "closures"


@pytest.mark.parametrize(
    "name, kind", [("four_bar_drake_ball.urdf", "spherical"), ("four_bar_gazebo_joint.urdf", "revolute")]
)
def test_the_four_bar_closed_by_another_tool_has_one_freedom_and_one_cut(name, kind):
    m = mechkit.load(CLOSURES / name)
    (cut,) = m.closures
    assert cut.kind == kind and m.home_mobility.dof == 1


def test_the_ball_s_frames_are_the_points_the_constraint_names():
    root = ET.parse(CLOSURES / "four_bar_drake_ball.urdf").getroot()
    (cut,) = read_tool_closures(root)
    origins = {
        j.find("child").get("link"): (j.find("parent").get("link"), j.find("origin").get("xyz"))
        for j in root.findall("joint")
    }
    assert origins[cut.frame_a][0] == "coupler_link" and origins[cut.frame_b][0] == "rocker_link"
    np.testing.assert_array_equal([float(v) for v in origins[cut.frame_a][1].split()], [0.28, 0, 0])
    np.testing.assert_array_equal([float(v) for v in origins[cut.frame_b][1].split()], [0.22, 0, 0])


def test_a_gazebo_joint_of_a_type_mechkit_cannot_cut_or_of_an_unknown_link_is_refused_by_name():
    robot = '<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="fixed"><parent link="a"/>'
    for inner, match in (
        ('<joint name="g" type="screw"><parent>a</parent><child>b</child></joint>', "gazebo/joint 'g'.*screw"),
        ('<joint name="g" type="ball"><parent>a</parent><child>c</child></joint>', "child 'c' is not a link"),
    ):
        root = ET.fromstring(f'{robot}<child link="b"/></joint><gazebo>{inner}</gazebo></robot>')
        with pytest.raises(MalformedDescription, match=match):
            read_tool_closures(root)
