"""`mechkit.sources.urdf`: loop declarations parsed into typed records, bad files named (never a
silently different mechanism), continuous joints as angles, actuators from the file or the call.

URDF (mechkit.sources.urdf): `<mimic>` read as a coupling row, and loops whose frames are joints.

The mimic row is checked against Pinocchio's own mimic joints (`buildModel(..., mimic=True)`, a
reduced model): the same mobility and the same motor torques holding gravity at rest.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import pytest
from tests_support import FIXTURES, PANDA, ROBOTS, SLIDER_CRANK, written

import mechkit
from mechkit.base.exceptions import MalformedDescription
from mechkit.base.resources import urdf_dir
from mechkit.catalog.registry import specs
from mechkit.cli import main
from mechkit.core.records import Coupling
from mechkit.report import report
from mechkit.sources.urdf import build_model, describe_urdf, parse_loops, read_urdf

from .independent import study, urdf_mimics


@pytest.mark.parametrize("name", list(specs()))
def test_loops_parse_into_typed_records(name):
    loops = parse_loops((urdf_dir() / f"{name}.urdf").read_text())
    assert loops, "a mechanism of mechkit has at least one loop closure"
    for loop in loops:
        assert loop.kind in ("revolute", "prismatic", "spherical", "hooke", "weld")


FOUR_BAR = (urdf_dir() / "four_bar.urdf").read_text()


FOUR_BAR_LOOP = (
    '<mechkit:loop axis="0 -1 0" frame_a="coupler_C" frame_b="rocker_C" name="C" rows="planar" type="revolute"/>'
)


@pytest.mark.parametrize(
    "replacement, message",
    [
        (FOUR_BAR_LOOP.replace('frame_b="rocker_C"', 'frame_b="nowhere"'), "frame_b 'nowhere' is not a link"),
        (FOUR_BAR_LOOP.replace('type="revolute"', 'type="screw"'), "type 'screw'"),
        (FOUR_BAR_LOOP.replace(' axis="0 -1 0"', ""), "missing attribute 'axis'"),
        (FOUR_BAR_LOOP.replace('axis="0 -1 0"', 'axis="0 0"'), "not a non-zero, finite 3-vector"),
        (FOUR_BAR_LOOP.replace('rows="planar"', 'rows="some"'), "rows 'some'"),
        (FOUR_BAR_LOOP.replace('frame_b="rocker_C"', 'frame_b="coupler_C"'), "the same link"),
    ],
)
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
    "mistyped namespace URI": (
        SLIDER_CRANK.replace('xmlns:mechkit="https://mechkit.dev/loop"', 'xmlns:mechkit="https://mechkit.dev/loops"'),
        "mechkit.dev/loops",
    ),
    "unknown element of the loop namespace": (
        SLIDER_CRANK.replace("<mechkit:loop ", "<mechkit:closure "),
        "mechkit:closure",
    ),
    "loop outside the namespace": (SLIDER_CRANK.replace("<mechkit:loop ", "<loop "), "<loop>"),
    "loop frame that does not exist": (
        SLIDER_CRANK.replace('frame_b="slider_pin"', 'frame_b="slider_pn"'),
        "slider_pn",
    ),
    "both frames on one body": (SLIDER_CRANK.replace('frame_b="slider_pin"', 'frame_b="rod_link"'), "one body"),
    "same frame twice": (SLIDER_CRANK.replace('frame_b="slider_pin"', 'frame_b="rod_tip"'), "same link"),
    "home of an unknown joint": (
        SLIDER_CRANK.replace('<mechkit:home joint="crank"', '<mechkit:home joint="crnk"'),
        "crnk",
    ),
    "transmission of an unknown joint": (
        SLIDER_CRANK.replace('<joint name="crank"><hardwareInterface>', '<joint name="crnk"><hardwareInterface>'),
        "crnk",
    ),
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
    text = (
        (FIXTURES / "slider_crank.urdf")
        .read_text()
        .replace('name="crank" type="revolute"', 'name="crank" type="continuous"')
    )
    (tmp_path / "sc.urdf").write_text(text)
    m = mechkit.load(tmp_path / "sc.urdf")
    assert m.model.nq == m.model.nv + 1
    assert m.joint_values(m.home_q)["crank"] == pytest.approx(0.5, abs=1e-15)
    i = m.q_index("crank")
    assert m.home_q[i : i + 2] == pytest.approx([np.cos(0.5), np.sin(0.5)], abs=1e-15)
    q = m.assemble({"crank": 2.0}, guess=m.home_q)
    assert m.joint_values(q)["crank"] == pytest.approx(2.0, abs=1e-14)
    assert report(m)["home"]["crank"] == pytest.approx(0.5, abs=1e-15)
    ref = mechkit.load(FIXTURES / "slider_crank.urdf")  # the same linkage with a revolute crank
    assert m.joint_values(q)["slider"] == pytest.approx(
        ref.joint_values(ref.assemble({"crank": 2.0}, guess=ref.home_q))["slider"], abs=1e-12
    )


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


TALOS_REDUCED = ROBOTS / "talos_data" / "robots" / "talos_reduced.urdf"
INERTIAL = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'


def _gripper(mimic: str, j2_type: str = "prismatic") -> str:
    """A base, two fingers on prismatic joints; finger2 carries `mimic`."""
    return f"""<robot name="gripper" xmlns:mechkit="https://mechkit.dev/loop">
      <link name="base"/><link name="finger1">{INERTIAL}</link><link name="finger2">{INERTIAL}</link>
      <joint name="j1" type="prismatic"><parent link="base"/><child link="finger1"/><axis xyz="0 1 0"/>
        <limit effort="10" lower="0" upper="0.04" velocity="1"/></joint>
      <joint name="j2" type="{j2_type}"><parent link="base"/><child link="finger2"/><axis xyz="0 -1 0"/>
        <limit effort="10" lower="0" upper="0.04" velocity="1"/>{mimic}</joint>
    </robot>"""


def test_a_mimic_is_a_coupling_row_with_urdf_defaults():
    full = describe_urdf(_gripper('<mimic joint="j1" multiplier="-2.5" offset="0.01"/>'), None, "urdf")
    bare = describe_urdf(_gripper('<mimic joint="j1"/>'), None, "urdf")
    assert full.couplings == (Coupling("j2", (("j2", 1.0),), (("j1", 1.0),), (0.01, -2.5)),)
    assert bare.couplings == (Coupling("j2", (("j2", 1.0),), (("j1", 1.0),), (0.0, 1.0)),)
    assert describe_urdf(_gripper(""), None, "urdf").couplings == ()


def test_panda_fingers_mimic_gives_pinocchios_own_mimic_model():
    """example-robot-data's Panda: finger_joint2 mimics finger_joint1. With the row, the tree of 9
    joints has 8 freedoms, as Pinocchio's mimic model has 8 velocities, and the 8 motors hold gravity
    with the torques Pinocchio's mimic model gives by RNEA: the fingers slide in opposite directions,
    so through the mimic their weights cancel on the finger motor."""
    desc = read_urdf(PANDA)
    assert list(desc.couplings) == urdf_mimics(PANDA)
    model = pin.buildModelFromUrdf(str(PANDA))
    reduced = pin.buildModelFromUrdf(str(PANDA), mimic=True)
    motors = [n for n in model.names[1:] if n != "panda_finger_joint2"]
    q0 = pin.neutral(model)
    q0[:7] = [0.3, -0.8, 0.5, -2.0, 0.4, 1.2, -0.6]  # fingers tilted: gravity acts along them
    q0[7] = 0.02
    found = study(model, [], motors, q0, couplings=desc.couplings)
    assert found.closed and found.q[8] == pytest.approx(found.q[7], abs=1e-12)
    assert found.dof == reduced.nv == 8
    assert found.holds and found.torques_unique
    expected = pin.rnea(reduced, reduced.createData(), found.q[:8], np.zeros(8), np.zeros(8))
    got = np.array([found.torques[n] for n in motors])
    weights = pin.rnea(model, model.createData(), found.q, np.zeros(9), np.zeros(9))[7:]
    assert abs(weights[0]) > 1e-3 and weights[1] == pytest.approx(
        -weights[0], abs=1e-12
    )  # tilted: each finger is loaded
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-10 * np.max(np.abs(expected)))


def test_a_mimic_on_a_fixed_joint_couples_nothing_and_a_mimic_of_a_fixed_joint_holds_the_offset():
    """example-robot-data's talos_reduced.urdf keeps the mimics of grippers it fixed: no row. A moving
    joint mimicking a fixed one follows its value, zero: the row holds it at the offset."""
    fixed = [
        j.get("name")
        for j in ET.parse(TALOS_REDUCED).getroot().iter("joint")
        if j.find("mimic") is not None and j.get("type") == "fixed"
    ]
    assert len(fixed) == 12
    assert read_urdf(TALOS_REDUCED).couplings == ()
    text = _gripper('<mimic joint="j1" multiplier="3" offset="0.02"/>').replace(
        'name="j1" type="prismatic"', 'name="j1" type="fixed"'
    )
    assert describe_urdf(text, None, "urdf").couplings == (Coupling("j2", (("j2", 1.0),), (), (0.02,)),)


MIMIC_ERRORS = {
    "mimic of a joint the URDF lacks": (_gripper('<mimic joint="j3"/>'), "joint='j3' is not a joint of the URDF"),
    "mimic of itself": (_gripper('<mimic joint="j2"/>'), "cannot mimic itself"),
    "multiplier not a number": (_gripper('<mimic joint="j1" multiplier="two"/>'), "multiplier 'two' is not a number"),
    "offset not finite": (_gripper('<mimic joint="j1" offset="inf"/>'), "offset 'inf' is not finite"),
    "mimic on a floating joint": (_gripper('<mimic joint="j1"/>', "floating"), "joint 'j2' is floating"),
    "mimics forming a cycle": (
        _gripper('<mimic joint="j1"/>').replace(
            '<limit effort="10" lower="0" upper="0.04" velocity="1"/></joint>\n      <joint name="j2"',
            (
                '<limit effort="10" lower="0" upper="0.04" velocity="1"/><mimic joint="j2"/></joint>\n'
                '      <joint name="j2"'
            ),
        ),
        "cycle",
    ),
}


@pytest.mark.parametrize("case", list(MIMIC_ERRORS))
def test_a_malformed_mimic_is_one_named_line_from_the_cli(case, tmp_path, capsys):
    text, needle = MIMIC_ERRORS[case]
    (tmp_path / "gripper.urdf").write_text(text)
    assert main(["report", str(tmp_path / "gripper.urdf")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "<mimic>" in err[0] and needle in err[0], err


FOUR_BAR_AT_JOINTS = """<robot name="fb" xmlns:mechkit="https://mechkit.dev/loop">
  <link name="ground"/><link name="crank">{i}</link><link name="coupler">{i}</link><link name="rocker">{i}</link>
  <joint name="A" type="revolute"><parent link="ground"/><child link="crank"/><axis xyz="0 0 1"/>
    <limit effort="1" lower="-3" upper="3" velocity="1"/></joint>
  <joint name="B" type="revolute"><parent link="crank"/><child link="coupler"/>
    <origin xyz="0.2 0 0"/><axis xyz="0 0 1"/>
    <limit effort="1" lower="-3" upper="3" velocity="1"/></joint>
  <joint name="D" type="revolute"><parent link="ground"/><child link="rocker"/>
    <origin xyz="0.6 0 0"/><axis xyz="0 0 1"/>
    <limit effort="1" lower="-3" upper="3" velocity="1"/></joint>
  <link name="coupler_tip"/><joint name="C_on_coupler" type="fixed"><parent link="coupler"/><child link="coupler_tip"/>
    <origin xyz="0.5 0 0"/></joint>
  <link name="rocker_tip"/><joint name="C_on_rocker" type="fixed"><parent link="rocker"/><child link="rocker_tip"/>
    <origin xyz="0.3 0 0"/></joint>
  LOOP
</robot>""".replace("{i}", INERTIAL)


def test_loop_frames_may_be_joints_as_pinocchio_names_them():
    """A loop between two fixed joints' frames (Gepetto's files close loops at joint frames) is the
    same loop as between their child links: Pinocchio puts both frames at one place."""
    by_joint = parse_loops(
        FOUR_BAR_AT_JOINTS.replace(
            "LOOP", '<mechkit:loop name="C" type="spherical" frame_a="C_on_coupler" frame_b="C_on_rocker"/>'
        )
    )
    assert [(c.frame_a, c.frame_b) for c in by_joint] == [("C_on_coupler", "C_on_rocker")]
    model = pin.buildModelFromXML(FOUR_BAR_AT_JOINTS.replace("LOOP", ""))
    for joint, link in (("C_on_coupler", "coupler_tip"), ("C_on_rocker", "rocker_tip")):
        a, b = (model.frames[model.getFrameId(n)] for n in (joint, link))
        assert a.parentJoint == b.parentJoint and a.placement.isApprox(b.placement, 1e-15)


def test_a_name_of_both_a_link_and_an_unrelated_joint_is_refused_as_a_loop_frame():
    text = FOUR_BAR_AT_JOINTS.replace(
        '<link name="rocker_tip"/>',
        '<link name="rocker_tip"/><link name="B_x"/>'
        '<joint name="B_x_fixed" type="fixed"><parent link="rocker"/><child link="B_x"/></joint>',
    )
    text = text.replace('name="B" type="revolute"', 'name="rocker_tip" type="revolute"').replace(
        "LOOP", ('<mechkit:loop name="C" type="spherical" frame_a="C_on_coupler" frame_b="rocker_tip"/>')
    )
    with pytest.raises(MalformedDescription, match="names both a link and a joint"):
        parse_loops(text)


def test_a_lever_mimic_loads_its_leader_by_the_multiplier():
    """Two vertical sliders, the second mimicking the first with multiplier 2.5 and offset 0.01 m: the
    motor of the first holds its own weight and 2.5 times the second's (virtual work), as Pinocchio's
    mimic model gives, and the closed configuration puts the second at 2.5 x + 0.01."""
    text = _gripper('<mimic joint="j1" multiplier="2.5" offset="0.01"/>').replace(
        '<axis xyz="0 1 0"/>', '<axis xyz="0 0 1"/>'
    )
    text = text.replace('<axis xyz="0 -1 0"/>', '<axis xyz="0 0 1"/>')
    desc = describe_urdf(text, None, "urdf")
    model, reduced = pin.buildModelFromXML(text), pin.buildModelFromXML(text, mimic=True)
    found = study(model, [], ["j1"], np.array([0.015, 0.0]), couplings=desc.couplings)
    assert found.closed and found.q[1] == pytest.approx(2.5 * found.q[0] + 0.01, abs=1e-12)
    assert found.dof == reduced.nv == 1 and found.holds
    expected = pin.rnea(reduced, reduced.createData(), found.q[:1], np.zeros(1), np.zeros(1))[0]
    assert expected == pytest.approx(9.81 * (1 + 2.5), rel=1e-12)
    assert found.torques["j1"] == pytest.approx(expected, rel=1e-12)


def test_a_spring_on_a_loop_cut_joint_acts_in_the_statics_as_its_potential_says(tmp_path):
    """The four-bar's URDF with `<mechkit:spring joint="C">` on its loop-cut pin: the crank's holding torque at
    rest grows, over the file without it, by the spring potential's slope along the closed motion, dV/d crank
    = k (x_C - ref) dx_C/d crank, x_C the cut's angle and its slope a central difference of assembled poses."""
    plain = (urdf_dir() / "four_bar.urdf").read_text()
    spring = '<mechkit:spring joint="C" stiffness="2.0" reference="0.3"/>\n  <mechkit:loop '
    sprung = mechkit.load(written(tmp_path, plain.replace("<mechkit:loop ", spring, 1), "sprung.urdf"))
    bare = mechkit.load(written(tmp_path, plain, "bare.urdf"))
    cut = sprung.closure_model.kernel.cuts[0]
    assert cut.closure.name == "C"
    data = sprung.model.createData()

    def angle_c(crank: float) -> float:
        q = sprung.assemble({"crank": crank})
        pin.framesForwardKinematics(sprung.model, data, q)
        R = data.oMf[cut.frame_a].rotation.T @ data.oMf[cut.frame_b].rotation
        return float(np.arctan2(R[2, 0] - R[0, 2], R[0, 0] + R[2, 2]) * -np.asarray(cut.closure.axis)[1])

    crank, h = 0.7, 1e-5
    slope = (angle_c(crank + h) - angle_c(crank - h)) / (2 * h)
    q = sprung.assemble({"crank": crank})
    zero = np.zeros(sprung.model.nv)
    held = (
        sprung.inverse_dynamics(q, zero, zero).efforts["crank"] - bare.inverse_dynamics(q, zero, zero).efforts["crank"]
    )
    expected = 2.0 * (angle_c(crank) - 0.3) * slope
    assert abs(expected) > 0.05  # the spring loads the crank
    assert held == pytest.approx(expected, rel=1e-7)


def test_a_spring_on_a_name_no_joint_or_loop_has_is_refused(tmp_path):
    plain = (urdf_dir() / "four_bar.urdf").read_text()
    text = plain.replace(
        "<mechkit:loop ", '<mechkit:spring joint="E" stiffness="2.0" reference="0"/>\n  <mechkit:loop '
    )
    with pytest.raises(MalformedDescription, match="mechkit:spring 'E'.*nor a revolute or prismatic loop"):
        mechkit.load(written(tmp_path, text))
