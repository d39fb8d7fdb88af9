"""onshape-to-robot's closing frames in a URDF (tests/fixtures/onshape/four_bar.urdf, written in its
conventions) read as loop closures: one hinge, one freedom, and the holding effort MuJoCo gives for the same
mechanism as onshape-to-robot writes it in MJCF (four_bar.xml: two `connect`s by site), and the one the same
URDF gives with the loop declared as `<mechkit:loop>`."""

from __future__ import annotations

import dataclasses
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from tests_support import FIXTURES, written

import mechkit
from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.onshape_closures import closing_frames
from mechkit.sources.urdf import LOOP_NAMESPACE, build_model, read_urdf

from .description_reference import Statics

ONSHAPE = FIXTURES / "onshape"
URDF = (ONSHAPE / "four_bar.urdf").read_text()
DECLARED = (  # the same loop as mechkit:loop: the hinge about closing_C_1's z axis
    f'<robot name="onshape_four_bar" xmlns:mechkit="{LOOP_NAMESPACE}">',
    '<mechkit:loop name="C" type="revolute" frame_a="closing_C_1" frame_b="closing_C_2" axis="0 0 1"/></robot>',
)


def _statics(path: Path) -> Statics:
    """The independent statics of a URDF with the crank driven (onshape-to-robot writes no transmission)."""
    desc = read_urdf(path)
    return Statics(dataclasses.replace(desc, model=build_model(desc.urdf), actuated=("crank",)))


def _declared(text: str) -> str:
    """The URDF with its loop declared as `<mechkit:loop>` and no closing frame left to read."""
    text = text.replace('<robot name="onshape_four_bar">', DECLARED[0]).replace("</robot>", DECLARED[1])
    return re.sub(r"closing_C_([12])_z", r"dummy_\1", text)


def test_the_closing_frames_are_one_hinge_with_one_freedom():
    """closing_C_1 / closing_C_2 with their _z pair: one revolute cut about closing_C_1's z axis (world y);
    the Kutzbach count and the numerical DOF 1 (two balls would count -1)."""
    (cut,) = read_urdf(ONSHAPE / "four_bar.urdf").closures
    assert (cut.name, cut.kind, cut.frame_a, cut.frame_b) == ("closing_C", "revolute", "closing_C_1", "closing_C_2")
    np.testing.assert_allclose(cut.axis, [0.0, 0.0, 1.0], atol=1e-15)
    m = mechkit.load(ONSHAPE / "four_bar.urdf", actuated=["crank"])
    assert m.home_mobility.dof == 1 == m.structure.kutzbach


def test_the_holding_effort_is_mujocos_and_the_declared_loops(tmp_path):
    """At the file's pose and three assembled crank angles, the crank effort that holds the four-bar
    against gravity equals MuJoCo's on four_bar.xml (its own least-squares statics: actuator moments and
    equality rows) to 1e-12 N m, the URDF's 1e-9 kg dummy links made massless as MuJoCo's sites are; and
    equals, dummies kept, the effort with the loop declared as <mechkit:loop> (1e-12 N m)."""
    from .mujoco_reference import MujocoReference

    pytest.importorskip("mujoco")
    massless = _statics(written(tmp_path, URDF.replace('<mass value="1e-9"/>', '<mass value="0"/>'), "massless.urdf"))
    as_written = _statics(ONSHAPE / "four_bar.urdf")
    declared = _statics(written(tmp_path, _declared(URDF), "declared.urdf"))
    assert [c.kind for c in declared.desc.closures] == ["revolute"] and declared.desc.closures[0].name == "C"
    ref = MujocoReference(ONSHAPE / "four_bar.xml", massless.model)
    efforts = []
    for crank in (None, 0.5, -0.8, 2.0):
        q = massless.configuration({})
        if crank is not None:
            q = massless.assemble(q, {"crank": crank})
        assert np.max(np.abs(massless.rows(q)[0])) < 1e-12 and massless.mobility(q) == 1
        u, left = massless.efforts(q)
        u_mj, left_mj = ref.efforts(q)
        assert left < 1e-12 and left_mj < 1e-12
        assert u[0] == pytest.approx(ref.in_our_units(u_mj)[0], abs=1e-12)
        assert as_written.efforts(q)[0][0] == pytest.approx(declared.efforts(q)[0][0], abs=1e-12)
        efforts.append(u[0])
    assert np.ptp(efforts) > 0.1  # the effort changes with the pose: the comparison is not of zeros


def test_without_the_z_pair_the_closure_is_a_ball_and_a_declared_loop_wins(tmp_path):
    """A ball, fastened or slider mate leaves only closing_C_1 / closing_C_2: a spherical cut (closed at
    the file's pose, one freedom: the loop is planar); a <mechkit:loop> on the pair replaces the reading."""
    text = re.sub(r"closing_C_([12])_z", r"dummy_\1", URDF)
    (cut,) = read_urdf(written(tmp_path, text, "ball.urdf")).closures
    assert cut.kind == "spherical" and cut.axis is None
    assert mechkit.load(tmp_path / "ball.urdf").home_mobility.dof == 1
    root = ET.fromstring(_declared(URDF))
    assert [c.kind for c in closing_frames(root)] == ["spherical"]
    assert closing_frames(root, read_urdf(written(tmp_path, _declared(URDF), "d.urdf")).closures) == ()


@pytest.mark.parametrize(
    "edit, needle",
    [
        (
            lambda t: t.replace('name="closing_C_2"', 'name="other"').replace('link="closing_C_2"', 'link="other"'),
            "without its other half closing_C_2",
        ),
        (
            lambda t: t.replace(
                '<parent link="rocker"/>\n    <child link="closing_C_2_z"/>',
                '<parent link="base_link"/>\n    <child link="closing_C_2_z"/>',
            ),
            "does not move with 'closing_C_2'",
        ),
        (
            lambda t: t.replace(
                "-0.038894251654084 0.1 0.2469559417958369", "-0.038894251654084 0.2 0.2469559417958369"
            ),
            "do not mark one hinge axis",
        ),
    ],
    ids=["half", "other part", "two axes"],
)
def test_closing_frames_mechkit_cannot_pair_are_refused_by_name(edit, needle, tmp_path):
    with pytest.raises(MalformedDescription, match=re.escape(needle)):
        read_urdf(written(tmp_path, edit(URDF), "bad.urdf"))


def test_the_pages_hand_closings_of_a_cad_export_hold_as_onshapes(tmp_path):
    """docs/your_own_mechanism.md closes a CAD export (the four-bar without closing frames) by hand, with a
    <mechkit:loop> and with an Extended-URDF sidecar: each, pasted into the exporter's tree, loads with one
    hinge loop, DOF 1, the rocker where the onshape closing frames put it and the crank held with their effort
    (1e-12; their 1e-9 kg dummy links made massless, as the page's frames are)."""
    from tests_support import ROOT

    page = (ROOT / "docs" / "your_own_mechanism.md").read_text()
    section = page[page.index("## CAD exports") :]
    xml = re.search(r"```xml\n(.*?)```", section, re.DOTALL)[1]
    sidecar = re.search(r"```yaml\n(.*?)```", section, re.DOTALL)[1]
    tree = re.sub(r"  <!-- Frame closing_C.*?</joint>\n", "", URDF, flags=re.DOTALL)
    assert 'link name="closing' not in tree
    added = xml[xml.index("  <link name=") : xml.index("</robot>")]
    hand = tree.replace('<robot name="onshape_four_bar">', xml.split("\n")[0]).replace("</robot>", added + "</robot>")
    y_frames = "".join(
        f'<link name="{name}_y"/><joint name="{name}_y_frame" type="fixed"><origin xyz="0 1 0"/>'
        f'<parent link="{name}"/><child link="{name}_y"/></joint>'
        for name in ("pin_C_coupler", "pin_C_rocker")
    )
    with_sidecar = re.sub(r"\s*<mechkit:loop .*?/>", y_frames, hand).replace(
        ' xmlns:mechkit="https://mechkit.dev/loop"', ""
    )
    folder = tmp_path / "sidecar"
    folder.mkdir()
    (folder / "four_bar.yaml").write_text(sidecar)
    massless = written(tmp_path, URDF.replace('<mass value="1e-9"/>', '<mass value="0"/>'), "massless.urdf")
    onshape = mechkit.load(massless, actuated=["crank"])  # its dummy links weigh 1e-9 kg, the page's nothing
    q_onshape = onshape.assemble({"crank": 0.5}, guess=onshape.home_q)
    zero = np.zeros(onshape.model.nv)
    held = onshape.inverse_dynamics(q_onshape, zero, zero).efforts["crank"]
    for path in (written(tmp_path, hand, "four_bar.urdf"), written(folder, with_sidecar, "four_bar.urdf")):
        m = mechkit.load(path, actuated=["crank"])
        assert m.home_mobility.dof == 1 == m.structure.kutzbach and [c.closure.kind for c in m.cuts] == ["revolute"]
        q = m.assemble({"crank": 0.5}, guess=m.home_q)
        np.testing.assert_allclose(m.joint_values(q)["rocker"], onshape.joint_values(q_onshape)["rocker"], atol=1e-12)
        assert m.inverse_dynamics(q, zero, zero).efforts["crank"] == pytest.approx(held, abs=1e-12)
    assert abs(held) > 0.1
