"""`mechkit.sources.urdf`: loop declarations parsed into typed records, bad files named (never a
silently different mechanism), continuous joints as angles, actuators from the file or the call."""

from __future__ import annotations

import numpy as np
import pytest
from tests_support import FIXTURES, SLIDER_CRANK, written

import mechkit
from mechkit.base.exceptions import MalformedDescription
from mechkit.base.resources import urdf_dir
from mechkit.catalog.registry import specs
from mechkit.report import report
from mechkit.sources.urdf import build_model, parse_loops


@pytest.mark.parametrize("name", list(specs()))
def test_loops_parse_into_typed_records(name):
    loops = parse_loops((urdf_dir() / f"{name}.urdf").read_text())
    assert loops, "a mechanism of mechkit has at least one loop closure"
    for loop in loops:
        assert loop.kind in ("revolute", "prismatic", "spherical", "hooke", "weld")


FOUR_BAR = (urdf_dir() / "four_bar.urdf").read_text()


FOUR_BAR_LOOP = '<mechkit:loop axis="0 -1 0" frame_a="coupler_C" frame_b="rocker_C" name="C" rows="planar" type="revolute"/>'


@pytest.mark.parametrize("replacement, message", [
    (FOUR_BAR_LOOP.replace('frame_b="rocker_C"', 'frame_b="nowhere"'), "frame_b 'nowhere' is not a link"),
    (FOUR_BAR_LOOP.replace('type="revolute"', 'type="screw"'), "type 'screw'"),
    (FOUR_BAR_LOOP.replace(' axis="0 -1 0"', ""), "missing attribute 'axis'"),
    (FOUR_BAR_LOOP.replace('axis="0 -1 0"', 'axis="0 0"'), "not a non-zero 3-vector"),
    (FOUR_BAR_LOOP.replace('rows="planar"', 'rows="some"'), "rows 'some'"),
    (FOUR_BAR_LOOP.replace('frame_b="rocker_C"', 'frame_b="coupler_C"'), "the same link"),
])
def test_malformed_loop_declarations_are_named(replacement, message):
    assert FOUR_BAR_LOOP in FOUR_BAR
    with pytest.raises(MalformedDescription, match=message):
        parse_loops(FOUR_BAR.replace(FOUR_BAR_LOOP, replacement))


def test_urdfdom_complaints_are_errors():
    broken = FOUR_BAR.replace('<joint name="coupler" type="revolute">', '<joint name="coupler" type="revolving">')
    with pytest.raises(MalformedDescription):
        build_model(broken)


def test_not_xml_is_an_error():
    with pytest.raises(MalformedDescription, match="not well-formed"):
        parse_loops("<robot><link></robot>")


SLIDER_LOOP = '<mechkit:loop name="pin" type="revolute" frame_a="rod_tip" frame_b="slider_pin" axis="0 -1 0"/>'


URDF_CASES = {
    "mistyped namespace URI": (SLIDER_CRANK.replace('xmlns:mechkit="https://mechkit.dev/loop"', 'xmlns:mechkit="https://mechkit.dev/loops"'),
                               "mechkit.dev/loops"),
    "unknown element of the loop namespace": (SLIDER_CRANK.replace("<mechkit:loop ", "<mechkit:closure "), "mechkit:closure"),
    "loop outside the namespace": (SLIDER_CRANK.replace("<mechkit:loop ", "<loop "), "<loop>"),
    "loop frame that does not exist": (SLIDER_CRANK.replace('frame_b="slider_pin"', 'frame_b="slider_pn"'), "slider_pn"),
    "both frames on one body": (SLIDER_CRANK.replace('frame_b="slider_pin"', 'frame_b="rod_link"'), "one body"),
    "same frame twice": (SLIDER_CRANK.replace('frame_b="slider_pin"', 'frame_b="rod_tip"'), "same link"),
    "home of an unknown joint": (SLIDER_CRANK.replace('<mechkit:home joint="crank"', '<mechkit:home joint="crnk"'), "crnk"),
    "transmission of an unknown joint": (SLIDER_CRANK.replace('<joint name="crank"><hardwareInterface>', '<joint name="crnk"><hardwareInterface>'),
                                         "crnk"),
    "not XML": ("this is not a URDF", "not well-formed"),
    "empty": ("   \n", "empty"),
}


@pytest.mark.parametrize("case", list(URDF_CASES))
def test_bad_urdf_is_a_named_error(case, tmp_path):
    text, needle = URDF_CASES[case]
    with pytest.raises(MalformedDescription, match=needle.replace("(", r"\(")):
        mechkit.load(written(tmp_path, text))


def test_without_the_namespace_fix_the_loop_would_be_an_open_tree(tmp_path):
    """The reason the mistyped namespace is an error: the same file without its loop has mobility 3."""
    m = mechkit.load(written(tmp_path, SLIDER_CRANK.replace(SLIDER_LOOP, "")))
    assert m.mobility().dof == 3


def test_a_continuous_joint_is_an_angle_at_the_boundary(tmp_path):
    """Pinocchio gives a continuous joint (cos, sin); inputs, home and reports use the angle."""
    text = (FIXTURES / "slider_crank.urdf").read_text().replace('name="crank" type="revolute"', 'name="crank" type="continuous"')
    (tmp_path / "sc.urdf").write_text(text)
    m = mechkit.load(tmp_path / "sc.urdf")
    assert m.model.nq == m.model.nv + 1
    assert m.joint_values(m.home_q)["crank"] == pytest.approx(0.5, abs=1e-15)
    i = m.q_index("crank")
    assert m.home_q[i:i + 2] == pytest.approx([np.cos(0.5), np.sin(0.5)], abs=1e-15)
    q = m.assemble({"crank": 2.0}, guess=m.home_q)
    assert m.joint_values(q)["crank"] == pytest.approx(2.0, abs=1e-14)
    assert report(m)["home"]["crank"] == pytest.approx(0.5, abs=1e-15)
    ref = mechkit.load(FIXTURES / "slider_crank.urdf")  # the same linkage with a revolute crank
    assert m.joint_values(q)["slider"] == pytest.approx(ref.joint_values(ref.assemble({"crank": 2.0}, guess=ref.home_q))["slider"], abs=1e-12)


def test_actuators_come_from_the_file_or_the_override_and_an_unactuated_model_says_so(tmp_path):
    text = (FIXTURES / "slider_crank.urdf").read_text()
    start, end = text.index("<transmission"), text.index("</transmission>") + len("</transmission>")
    (tmp_path / "bare.urdf").write_text(text[:start] + text[end:])
    bare = mechkit.load(tmp_path / "bare.urdf")
    assert bare.actuated == () and report(bare)["actuated"] == []
    with pytest.raises(mechkit.InvalidParameters, match="unactuated"):
        bare.velocities(bare.home_q, [1.0])
    driven = mechkit.load(tmp_path / "bare.urdf", actuated=["slider"])
    assert driven.actuated == ("slider",)
    assert mechkit.load("four_bar", actuated=["rocker"]).actuated == ("rocker",)
