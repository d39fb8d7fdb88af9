"""The SDFormat reader: two small loop fixtures against Pinocchio models built by hand from their
dimensions, example-robot-data's Cassie files (they load, close, report their DOF and idle
freedoms, and hold gravity with the pelvis fixed, the efforts checked against virtual work), and
malformed files refused in one line.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from tests_support import FIXTURES, ROBOTS, physical_cassie_sdf

from mechkit.base.exceptions import MalformedDescription
from mechkit.core.records import Coupling, JointSpring, LoopClosure
from mechkit.sources.description import Description
from mechkit.sources.sdf import read_sdf

from .description_reference import Statics
from .field_cli import refusal

FIXTURES = FIXTURES / "field" / "sdf"
CASSIE = ROBOTS / "cassie_description" / "robots"
Y, Z = np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0])


def _ry(degrees: float) -> np.ndarray:
    return pin.rpy.rpyToMatrix(0.0, np.radians(degrees), 0.0)


def _inertia(mass, com, diagonal, rpy=(0.0, 0.0, 0.0), ixy=0.0) -> pin.Inertia:
    R = pin.rpy.rpyToMatrix(*rpy)
    I = np.diag(diagonal) + ixy * (np.outer([1, 0, 0], [0, 1, 0]) + np.outer([0, 1, 0], [1, 0, 0]))
    return pin.Inertia(mass, np.asarray(com, dtype=float), R @ I @ R.T)


def _four_bar_by_hand() -> Description:
    """The four-bar fixture built from its dimensions, each joint frame at its link's frame (the
    reader puts them elsewhere: only world placements may agree)."""
    W = pin.SE3(pin.rpy.rpyToMatrix(0, 0, np.pi / 2), np.array([1.0, 2.0, 0.0])) * pin.SE3(
        np.eye(3), np.array([0, 0, 0.5])
    )
    a, b, c, psi = 0.1, 0.23134365934659912, 0.2, 39.43868642253353
    B = a * np.array([np.cos(np.radians(30)), 0.0, np.sin(np.radians(30))])
    m = pin.Model()
    m.appendBodyToJoint(0, pin.Inertia(2.0, np.zeros(3), 0.1 * np.eye(3)), W)
    crank_frame = W * pin.SE3(_ry(-30), np.zeros(3))
    crank = m.addJoint(0, pin.JointModelRY(), crank_frame, "crank_joint")
    m.appendBodyToJoint(crank, _inertia(0.05, [0.05, 0, 0], [1e-5, 5e-5, 5e-5]), pin.SE3.Identity())
    coupler_frame = W * pin.SE3(_ry(-psi), B)
    coupler = m.addJoint(crank, pin.JointModelRY(), crank_frame.actInv(coupler_frame), "coupler_joint")
    m.appendBodyToJoint(
        coupler,
        _inertia(0.12, [0.115671829673, 0, 0.01], [2e-5, 6e-4, 6e-4], (0, 0, np.radians(20)), 1e-6),
        pin.SE3.Identity(),
    )
    rocker = m.addJoint(0, pin.JointModelRY(), W * pin.SE3(_ry(-100), np.array([0.3, 0, 0])), "rocker_joint")
    m.appendBodyToJoint(rocker, _inertia(0.09, [0.1, 0, 0], [1e-5, 3e-4, 3e-4]), pin.SE3.Identity())
    rotor = m.addJoint(0, pin.JointModelRY(), W, "motor")
    m.appendBodyToJoint(rotor, _inertia(0.02, [0, 0, 0], [1e-6, 2e-6, 1e-6]), pin.SE3.Identity())
    for name, joint in (("crank", crank), ("coupler", coupler), ("rocker", rocker), ("rotor", rotor)):
        m.addFrame(pin.Frame(name, joint, 0, pin.SE3.Identity(), pin.FrameType.BODY), False)
    m.addFrame(
        pin.Frame("C_on_coupler", coupler, 0, pin.SE3(np.eye(3), np.array([b, 0, 0])), pin.FrameType.OP_FRAME), False
    )
    m.addFrame(
        pin.Frame("C_on_rocker", rocker, 0, pin.SE3(_ry(100 - psi), np.array([c, 0, 0])), pin.FrameType.OP_FRAME), False
    )
    cut = LoopClosure("C", "revolute", "C_on_coupler", "C_on_rocker", Y)
    gear = Coupling("gear", (("crank_joint", 1.0),), (("motor", 1.0),), (0.0, -0.1))
    return Description(
        "by hand",
        None,
        ("motor",),
        closures=(cut,),
        model=m,
        couplings=(gear,),
        springs=(JointSpring("rocker_joint", 2.0, 0.1, 0.0, 0.05),),
    )


def _rssr_by_hand() -> Description:
    m = pin.Model()
    crank = m.addJoint(0, pin.JointModelRZ(), pin.SE3.Identity(), "crank_joint")
    m.appendBodyToJoint(crank, _inertia(0.06, [0.05, 0, 0], [2e-6, 6e-5, 6e-5]), pin.SE3.Identity())
    coupler = m.addJoint(crank, pin.JointModelUniversal(Z, Y), pin.SE3(np.eye(3), np.array([0.1, 0, 0])), "B")
    m.appendBodyToJoint(
        coupler, _inertia(0.21, [0.125, 0.05, 0.06], [7e-6, 2.7e-3, 2.7e-3], (0.3, -0.4, 0.2)), pin.SE3.Identity()
    )
    rocker = m.addJoint(0, pin.JointModelRY(), pin.SE3(np.eye(3), np.array([0.35, 0.1, 0])), "rocker_joint")
    m.appendBodyToJoint(rocker, _inertia(0.09, [0, 0, 0.06], [1e-4, 1e-4, 3e-6]), pin.SE3.Identity())
    for name, joint in (("crank", crank), ("coupler", coupler), ("rocker", rocker)):
        m.addFrame(pin.Frame(name, joint, 0, pin.SE3.Identity(), pin.FrameType.BODY), False)
    m.addFrame(
        pin.Frame("Ca", coupler, 0, pin.SE3(np.eye(3), np.array([0.25, 0.1, 0.12])), pin.FrameType.OP_FRAME), False
    )
    m.addFrame(pin.Frame("Cb", rocker, 0, pin.SE3(np.eye(3), np.array([0, 0, 0.12])), pin.FrameType.OP_FRAME), False)
    return Description(
        "by hand",
        None,
        (),
        closures=(LoopClosure("C", "spherical", "Ca", "Cb"),),
        model=m,
        springs=(JointSpring("rocker_joint", 0.0, 0.0, 0.0, 0.02),),
    )


@pytest.mark.parametrize(
    "file, by_hand, driven",
    [
        ("four_bar_gearbox.sdf", _four_bar_by_hand, {"motor": 0.3}),
        ("rssr_universal.sdf", _rssr_by_hand, {"crank_joint": 0.4}),
    ],
)
def test_small_sdf_loops_agree_with_models_built_by_hand(file, by_hand, driven):
    """Frames of every link and inertias in the world at random coordinates, the closure, the gearbox
    coupling, the DOF, and the efforts holding gravity (and the rocker's spring) after assembly."""
    desc, hand = read_sdf(FIXTURES / file), by_hand()
    assert sorted(desc.model.names) == sorted(hand.model.names)
    assert [c.kind for c in desc.closures] == [c.kind for c in hand.closures]
    assert desc.couplings == hand.couplings and desc.springs == hand.springs and desc.actuated == hand.actuated
    rng = np.random.default_rng(7)
    ours, theirs = (
        Statics(desc, tuple(j for j in driven if j not in desc.actuated)),
        Statics(hand, tuple(j for j in driven if j not in hand.actuated)),
    )
    for _ in range(4):
        values = {
            hand.model.names[j]: (tuple(rng.uniform(-1, 1, 2)) if hand.model.joints[j].nq == 2 else rng.uniform(-1, 1))
            for j in range(1, hand.model.njoints)
        }
        q1, q2 = ours.configuration(values), theirs.configuration(values)
        d1, d2 = desc.model.createData(), hand.model.createData()
        pin.framesForwardKinematics(desc.model, d1, q1)
        pin.framesForwardKinematics(hand.model, d2, q2)
        for link in [f.name for f in hand.model.frames if f.type == pin.FrameType.BODY]:
            np.testing.assert_allclose(
                d1.oMf[desc.model.getFrameId(link, pin.FrameType.BODY)].homogeneous,
                d2.oMf[hand.model.getFrameId(link)].homogeneous,
                atol=1e-12,
            )
        for j in range(1, hand.model.njoints):
            k = desc.model.getJointId(hand.model.names[j])
            np.testing.assert_allclose(
                d1.oMi[k].act(desc.model.inertias[k]).matrix(),
                d2.oMi[j].act(hand.model.inertias[j]).matrix(),
                atol=1e-12,
            )
        np.testing.assert_allclose(ours.rows(q1)[0], theirs.rows(q2)[0], atol=1e-12)
        np.testing.assert_allclose(ours.generalised(q1), _reorder(theirs.generalised(q2), hand, desc), atol=1e-12)
    q1 = ours.assemble(ours.configuration(desc.guess), driven)
    q2 = theirs.assemble(theirs.configuration({}), driven)
    assert ours.mobility(q1) == theirs.mobility(q2) == 1 and ours.idle(q1) == theirs.idle(q2) == {}
    for j in range(1, hand.model.njoints):  # the same assembly
        k, a = desc.model.joints[desc.model.getJointId(hand.model.names[j])], hand.model.joints[j]
        np.testing.assert_allclose(q1[k.idx_q : k.idx_q + k.nq], q2[a.idx_q : a.idx_q + a.nq], atol=1e-10)
    u1, left1 = ours.efforts(q1)
    u2, left2 = theirs.efforts(q2)
    assert left1 < 1e-10 and left2 < 1e-10  # the driven joint holds it
    np.testing.assert_allclose(u1, u2, atol=1e-10 * max(1.0, np.max(np.abs(u2))))


def _reorder(values: np.ndarray, source: Description, target: Description) -> np.ndarray:
    """Velocity-ordered values of `source`'s model in `target`'s order (joints matched by name)."""
    out = np.zeros(target.model.nv)
    for j in range(1, source.model.njoints):
        a, k = source.model.joints[j], target.model.joints[target.model.getJointId(source.model.names[j])]
        out[k.idx_v : k.idx_v + k.nv] = values[a.idx_v : a.idx_v + a.nv]
    return out


def test_a_revolute2_joint_is_the_universal_joint_it_names(tmp_path):
    """SDFormat's revolute2 (two revolute axes in series, `axis` then `axis2`) written for the RSUR-S fixture's
    universal joint: the same Pinocchio model (placements of every joint at random configurations, to 1e-15)."""
    path = tmp_path / "revolute2.sdf"
    path.write_text(OLD.replace('<joint name="B" type="universal">', '<joint name="B" type="revolute2">'))
    two, universal = read_sdf(path), read_sdf(FIXTURES / "rssr_universal.sdf")
    assert two.model.nq == universal.model.nq and [c.kind for c in two.closures] == ["spherical"]
    rng = np.random.default_rng(7)
    for _ in range(5):
        q = rng.uniform(-np.pi, np.pi, two.model.nq)
        placements = []
        for desc in (two, universal):
            data = desc.model.createData()
            pin.forwardKinematics(desc.model, data, q)
            placements.append(np.array([m.homogeneous for m in data.oMi]))
        np.testing.assert_allclose(placements[0], placements[1], atol=1e-15)


@pytest.mark.parametrize("kind", ["universal", "revolute2"])
def test_a_two_axis_joint_with_axes_not_perpendicular_is_refused_by_name(tmp_path, kind):
    """Pinocchio's universal joint (and mechkit's Hooke cut) assume perpendicular axes; Pinocchio takes others
    in silence."""
    text = OLD.replace('<joint name="B" type="universal">', f'<joint name="B" type="{kind}">')
    path = tmp_path / "skew.sdf"
    path.write_text(text.replace("<axis2><xyz>0 1 0</xyz></axis2>", "<axis2><xyz>0 1 1</xyz></axis2>"))
    with pytest.raises(MalformedDescription, match="SDF joint 'B'.*not perpendicular"):
        read_sdf(path)


def test_a_universal_joint_cut_chosen_by_parent_guidance_gives_the_same_linkage(tmp_path):
    """The RSUR-S fixture rewritten with the ball joint running rocker -> coupler: the coupler then has
    two parent joints, and `parent_guidance` makes the ball its tree joint, so the universal joint is
    the cut (a Hooke closure). Same linkage: the same DOF, assembly and holding effort as the file."""
    text = OLD.replace(
        "<parent>coupler</parent>\n      <child>rocker</child>", "<parent>rocker</parent>\n      <child>coupler</child>"
    )
    text = text.replace("<pose>0 0 0.12 0 0 0</pose>", "<pose>0.25 0.1 0.12 0 0 0</pose>")
    path = tmp_path / "swapped.sdf"
    path.write_text(text)
    assert [c.kind for c in read_sdf(path).closures] == ["spherical"]  # without guidance the ball is the cut
    swapped, original = read_sdf(path, parent_guidance=["C"]), read_sdf(FIXTURES / "rssr_universal.sdf")
    (cut,) = swapped.closures
    assert (cut.name, cut.kind) == ("B", "hooke")
    np.testing.assert_allclose(cut.axis_a, Z, atol=1e-15)
    np.testing.assert_allclose(cut.axis_b, Y, atol=1e-15)
    efforts = []
    for desc in (swapped, original):
        st = Statics(desc, ("crank_joint",))
        q = st.assemble(st.configuration(desc.guess), {"crank_joint": 0.4})
        assert st.mobility(q) == 1 and st.idle(q) == {}
        data = desc.model.createData()
        pin.framesForwardKinematics(desc.model, data, q)
        efforts.append(
            (
                st.efforts(q),
                {
                    link: data.oMf[desc.model.getFrameId(link, pin.FrameType.BODY)].homogeneous
                    for link in ("crank", "coupler", "rocker")
                },
            )
        )
    (u1, left1), at1 = efforts[0]
    (u2, left2), at2 = efforts[1]
    for link in at1:
        np.testing.assert_allclose(at1[link], at2[link], atol=1e-10)
    assert left1 < 1e-12 and left2 < 1e-12
    np.testing.assert_allclose(u1, u2, atol=1e-10 * max(1.0, np.max(np.abs(u2))))


CASSIE_FACTS = {  # file -> (DOF floating or as written, DOF with the pelvis welded, loops, gearboxes)
    "cassie.sdf": (16, 10, ["prismatic", "revolute", "spherical"] * 2, 10),
    "cassie_v2.sdf": (18, 12, ["spherical"] * 4, 0),
    "cassie_reduced.sdf": (11, None, ["spherical"] * 4, 0),  # its pelvis slides on a vertical prismatic
    "cassie_simple.sdf": (11, None, ["revolute", "spherical"] * 2, 0),
    "cassie_wo_gearbox_spring.sdf": (13, None, ["revolute", "spherical"] * 2, 0),
}


def _welded(path: Path, tmp_path: Path) -> Path:
    """The file with its pelvis welded to the world where it is written."""
    out = tmp_path / f"welded_{path.name}"
    out.write_text(
        path.read_text().replace(
            "</model>",
            '<joint name="weld_pelvis" type="fixed"><parent>world</parent><child>pelvis</child></joint></model>',
        )
    )
    return out


def _cassie(file: str, tmp_path: Path) -> Path:
    """An example-robot-data Cassie file; cassie.sdf made physical (`tests_support.physical_cassie_sdf`)."""
    return physical_cassie_sdf(tmp_path) if file == "cassie.sdf" else CASSIE / file


@pytest.mark.parametrize("file", list(CASSIE_FACTS))
def test_example_robot_data_cassie_loads_closes_and_reports_its_dof(file, tmp_path):
    dof, welded_dof, loops, gearboxes = CASSIE_FACTS[file]
    source = _cassie(file, tmp_path)
    desc = read_sdf(source)
    assert sorted(c.kind for c in desc.closures) == sorted(loops) and len(desc.couplings) == gearboxes
    for d, expected in ((desc, dof), (read_sdf(_welded(source, tmp_path)), welded_dof)):
        if expected is None:
            continue
        st = Statics(d)
        q = st.configuration(d.guess)
        assert np.max(np.abs(st.rows(q)[0])) < 1e-12  # the file's own configuration is closed
        q = st.assemble(pin.integrate(d.model, q, 0.01 * np.ones(d.model.nv)), {})  # and it closes from nearby
        assert st.mobility(q) == expected and st.idle(q) == {}


def test_cassie_sdf_gearboxes_drive_its_outputs(tmp_path):
    """Each gearbox couples a rotor (`*-ip`, the actuated joint) to its output (`*-op`): output =
    -ratio * rotor (SDFormat's theta_2 = -gearbox_ratio theta_1)."""
    desc = read_sdf(_cassie("cassie.sdf", tmp_path))
    ratios = {"roll": 0.04, "yaw": 0.04, "pitch": 0.0625, "knee": 0.0625, "foot": 0.02}
    assert desc.actuated == tuple(f"{s}-{j}-ip" for s in ("left", "right") for j in ratios)
    for k in desc.couplings:
        ((rotor, s1),) = k.leader
        ((output, s2),) = k.follower
        assert rotor.endswith("-ip") and output == rotor.replace("-ip", "-op") and s1 == s2 == 1.0
        assert k.polynomial == (0.0, -ratios[rotor.split("-")[1]])


def test_cassie_sdf_with_the_pelvis_welded_holds_gravity_as_virtual_work_says(tmp_path):
    """At the file's configuration the rotors hold the legs (nothing is left unbalanced), and their
    efforts are the derivatives of the potential energy (gravity and springs) along the closed motions
    driven by each rotor: central differences of the energy of assembled configurations, Richardson-
    extrapolated (h = 2e-3, 1e-3). That check is good to about 1e-7 N m here, not 1e-10: each leg's
    loops are nearly singular (closure Jacobian singular values down to 3e-7 of the largest), so an
    assembly closed to 1e-14 still places the passive joints to ~1e-8 rad, which the differences of
    the energy turn into ~1e-7 N m; the bound below is 1e-6 of the largest effort."""
    desc = read_sdf(_welded(_cassie("cassie.sdf", tmp_path), tmp_path))
    st = Statics(desc)
    q = st.configuration(desc.guess)
    u, left = st.efforts(q)
    scale = float(np.max(np.abs(st.generalised(q))))
    assert left < 1e-8 * scale
    J = st.rows(q)[1]
    singular = np.linalg.svd(J, compute_uv=False)
    assert 1e-8 < singular[J.shape[1] - st.mobility(q) - 1] / singular[0] < 1e-6  # the conditioning said above

    def energy(q: np.ndarray) -> float:
        potential = pin.computePotentialEnergy(desc.model, desc.model.createData(), q)
        return potential + sum(0.5 * s.stiffness * (st.value(q, s.joint) - s.reference) ** 2 for s in desc.springs)

    def derivative(motor: str, h: float) -> float:
        at = {j: 0.0 for j in desc.actuated}
        ends = []
        for step in (h, -h):
            at[motor] = step
            ends.append(energy(st.assemble(q, at, tol=1e-14)))
        return (ends[0] - ends[1]) / (2 * h)

    for i, motor in enumerate(desc.actuated):
        work = (4 * derivative(motor, 1e-3) - derivative(motor, 2e-3)) / 3
        assert u[i] == pytest.approx(work, abs=1e-6 * max(1.0, np.max(np.abs(u)))), motor


GOOD = (FIXTURES / "four_bar_gearbox.sdf").read_text()
OLD = (FIXTURES / "rssr_universal.sdf").read_text()
MALFORMED = {  # file text -> what the one-line error says
    "": "empty",
    "<sdf version='1.9'><model>": "not well-formed",
    "<robot/>": "starts with <sdf>",
    "<sdf version='1.9'><world name='w'/></sdf>": "expected one <model>",
    GOOD.replace('<link name="base">', '<static>true</static><link name="base">'): "<static> is true",
    GOOD.replace('version="1.9"', 'version="latest"'): "expected a version",
    GOOD.replace('<link name="rotor">', '<model name="inner"/><link name="rotor">'): "a nested model without a link",
    GOOD.replace('<link name="rotor">', '<include><uri>arm</uri></include><link name="rotor">'): "<include> is not",
    OLD.replace("</model>\n</sdf>", '<model name="inner"><link name="l"/></model></model></sdf>'): "from SDFormat 1.8",
    GOOD.replace(
        '<link name="rotor">', '<model name="inner" placement_frame="l"><link name="l"/></model><link name="rotor">'
    ): "placement_frame is not read",
    GOOD.replace(
        '<link name="rotor">', '<model name="inner"><static>1</static><link name="l"/></model><link name="rotor">'
    ): "a <static> nested model",
    GOOD.replace('<link name="rocker">', '<link name="crank">'): "missing or repeated name",
    GOOD.replace(
        'type="revolute">\n      <pose relative_to="pivot_D"/>', 'type="screw">\n      <pose relative_to="pivot_D"/>'
    ): "type 'screw' is not read",
    GOOD.replace('<pose relative_to="pivot_D"/>', '<pose relative_to="pivot_E"/>'): "'pivot_E': no such frame",
    GOOD.replace(
        '<pose relative_to="base">0.3 0 0 0 0 0</pose>', '<pose relative_to="rocker_joint">0.3 0 0 0 0 0</pose>'
    ): "pose cycle: rocker_joint -> pivot_D -> rocker_joint",
    GOOD.replace("<parent>crank</parent>", "<parent>crank_link</parent>"): "<parent> 'crank_link' is not a link",
    GOOD.replace("<child>rotor</child>", "<child>world</child>"): "<child> 'world' is not a link",
    GOOD.replace(
        "<gearbox_reference_body>base", "<gearbox_reference_body>ground"
    ): "gearbox_reference_body 'ground' is not a link",
    GOOD.replace(
        "<gearbox_reference_body>base", "<gearbox_reference_body>rocker"
    ): "no revolute tree joint between gearbox_reference_body 'rocker' and 'rotor'",
    GOOD.replace(
        "<axis2><xyz>0 1 0</xyz></axis2>", "<axis2><xyz>1 0 0</xyz></axis2>"
    ): "<axis2> is not the axis of joint",
    GOOD.replace("<gearbox_ratio>0.1</gearbox_ratio>", ""): "missing <gearbox_ratio>",
    GOOD.replace('<axis><xyz expressed_in="__model__">0 1 0</xyz></axis>', ""): "missing <axis>",
    GOOD.replace(
        '<xyz>0 1 0</xyz></axis>\n    </joint>\n    <link name="rotor">',
        '<xyz>0 0 0</xyz></axis>\n    </joint>\n    <link name="rotor">',
    ): "<axis><xyz> is zero",
    GOOD.replace("<pose>0 0 0.5 0 0 0</pose>", "<pose>0 0 half 0 0 0</pose>"): "is not 6 numbers",
    GOOD.replace("<mass>0.09</mass>", "<mass>heavy</mass>"): "<mass> 'heavy' is not 1 numbers",
    OLD.replace("<pose>0 0 0.12 0 0 0</pose>", '<pose frame="rocker">0 0 0.12 0 0 0</pose>'): "<pose frame> attribute",
    OLD.replace(
        "<pose>0 0 0.12 0 0 0</pose>", '<pose relative_to="rocker">0 0 0.12 0 0 0</pose>'
    ): "needs SDFormat 1.7",
    OLD.replace(
        "<dynamics><damping>0.01</damping></dynamics>", "<dynamics><spring_stiffness>3</spring_stiffness></dynamics>"
    ): "a spring on a cut joint",
    OLD.replace(
        "<parent>world</parent>\n      <child>crank</child>", "<parent>coupler</parent>\n      <child>crank</child>"
    ): "reach neither the world nor a root",
}


@pytest.mark.parametrize("text, needle", MALFORMED.items(), ids=[f"s{i}" for i in range(len(MALFORMED))])
def test_malformed_sdf_is_refused_in_one_line_naming_the_element(text, needle, tmp_path):
    assert text != GOOD and text != OLD or not text  # each case changes its file
    path = tmp_path / "broken.sdf"
    path.write_text(text)
    with pytest.raises(MalformedDescription, match=re.escape(needle)) as err:
        read_sdf(path)
    assert refusal(path) == f"mechkit: error: {err.value}"  # the same one line from `mechkit report`


def test_mechkit_report_on_a_broken_sdf_says_it_in_one_line(tmp_path):
    path = tmp_path / "cycle.sdf"
    path.write_text(next(t for t, n in MALFORMED.items() if n.startswith("pose cycle")))
    out = subprocess.run(
        [sys.executable, "-m", "mechkit", "report", str(path)], capture_output=True, text=True, check=False
    )
    lines = out.stderr.strip().splitlines()
    assert out.returncode == 2 and len(lines) == 1 and "Traceback" not in out.stderr and "pose cycle" in lines[0]


def test_joints_listed_before_links_read_as_the_usual_order(tmp_path):
    """SDFormat puts no order on a model's elements: the four-bar with every joint first is the same model."""
    import mechkit

    source = FIXTURES / "four_bar_gearbox.sdf"
    text = source.read_text()
    joints = "".join(re.findall(r"    <joint .*?\n    </joint>\n", text, re.DOTALL))
    body = re.sub(r"    <joint .*?\n    </joint>\n", "", text, flags=re.DOTALL)
    reordered = tmp_path / "joints_first.sdf"
    reordered.write_text(
        body.replace('<model name="four_bar_gearbox">\n', '<model name="four_bar_gearbox">\n' + joints, 1)
    )
    a, b = mechkit.load(source), mechkit.load(reordered)
    assert b.model.nq == a.model.nq and b.home_mobility.dof == a.home_mobility.dof == 1
    assert np.allclose(sorted(b.home_q), sorted(a.home_q), atol=1e-12)


def test_several_free_roots_each_carry_their_subtree(tmp_path):
    """Two chains nothing joins (joints first): a free-flyer per root, each just before its own subtree
    (was: both free-flyers first, not depth first); 2 x 6 + 2 freedoms, and at the guess every link
    where the file puts it."""
    import mechkit

    path = tmp_path / "two_roots.sdf"
    path.write_text(
        '<sdf version="1.9"><model name="m">'
        '<joint name="jb" type="revolute"><parent>b</parent><child>b2</child><axis><xyz>0 0 1</xyz></axis></joint>'
        '<joint name="ja" type="revolute"><parent>a</parent><child>a2</child><axis><xyz>0 0 1</xyz></axis></joint>'
        '<link name="a"/><link name="b"><pose>1 0 0 0 0 0.5</pose></link><link name="a2"><pose>0 0 1 0 0 0</pose>'
        '</link><link name="b2"><pose relative_to="b">0 2 0 0 0 0</pose></link></model></sdf>'
    )
    desc = read_sdf(path)
    assert list(desc.model.names) == ["universe", "a_root_joint", "ja", "b_root_joint", "jb"]
    assert mechkit.load(path).home_mobility.dof == 14
    data = desc.model.createData()
    pin.framesForwardKinematics(desc.model, data, Statics(desc).configuration(desc.guess))
    where = {"a": (0, 0, 0), "b": (1, 0, 0), "a2": (0, 0, 1), "b2": (1 - 2 * np.sin(0.5), 2 * np.cos(0.5), 0)}
    for link, xyz in where.items():
        np.testing.assert_allclose(data.oMf[desc.model.getFrameId(link)].translation, xyz, atol=1e-15)
