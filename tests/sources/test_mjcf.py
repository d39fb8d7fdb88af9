"""The MJCF reader against MuJoCo's own functions on the same files: MuJoCo Menagerie's Cassie (floating
and with the pelvis fixed) and Robotiq 2F-85, and a file of every equality, tendon and spring kind.

Our side is `description_reference` (Pinocchio calls on the reader's model and records); MuJoCo's is
`mujoco_reference` (mj_forward's equality rows, bias and passive forces, actuator moments). The poses
are ones where the motors hold: Cassie's springs settled under its motors at the keyframe `home`,
the 2F-85 with its couplers on their upper stops (the spring pushes them there).
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from tests_support import FIXTURES, written

import mechkit

mujoco = pytest.importorskip("mujoco")

from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.mjcf import read_mjcf
from mechkit.sources.urdf import build_model

from .description_reference import Statics
from .field_cli import refusal
from .mujoco_reference import MujocoReference

MENAGERIE = FIXTURES / "field" / "menagerie"
CASSIE = MENAGERIE / "agility_cassie" / "cassie.xml"
GRIPPER = MENAGERIE / "robotiq_2f85" / "2f85.xml"
STOPS = ("right_coupler_joint", "left_coupler_joint")
TOL = 1e-8


def _fixed_cassie(tmp_path: Path) -> Path:
    """Cassie with the pelvis welded where it is written (no free joint; the keyframe, sized for the
    free joint, dropped)."""
    text = re.sub(r"<keyframe>.*</keyframe>", "", CASSIE.read_text().replace("<freejoint/>", ""), flags=re.DOTALL)
    path = tmp_path / "cassie_fixed.xml"
    path.write_text(text)
    return path


def _cassie_pose(desc, st: Statics) -> np.ndarray:
    """Cassie's keyframe `home`, its motors held there and its springs settled (Newton)."""
    key = MujocoReference(CASSIE, read_mjcf(CASSIE).model)
    home = {j: v for j, v in key.joint_values(key.mm.key_qpos[0]).items() if desc.model.existJointName(j)}
    q = st.assemble(st.configuration(home), {})
    return st.equilibrium(q, {j: st.value(q, j) for j in desc.actuated})


@pytest.mark.parametrize("path", [CASSIE, GRIPPER], ids=["cassie", "2f85"])
def test_the_fixture_compiles_to_the_original_inertias_and_the_reader_keeps_them(path):
    """The stripped fixture compiles to the inertias of the unmodified file (recorded), and each
    Pinocchio joint carries, in the world at qpos0, the mass, centre of mass and rotational inertia of
    the MuJoCo bodies welded to it (MuJoCo's body_weldid, xipos, ximat)."""
    recorded = json.loads((path.parent / "original_inertias.json").read_text())
    desc = read_mjcf(path)
    ref = MujocoReference(path, desc.model)
    for body, now in ref.inertias().items():
        was = recorded[body]
        assert now["mass"] == pytest.approx(was["mass"], rel=1e-12, abs=1e-15), body
        np.testing.assert_allclose(now["com"], was["com"], atol=1e-12)
        np.testing.assert_allclose(
            now["inertia"], was["inertia"], atol=1e-12 * max(1e-9, np.max(np.abs(was["inertia"])))
        )
    q = Statics(desc).configuration(desc.guess)
    ref.at(q)
    data = desc.model.createData()
    pin.forwardKinematics(desc.model, data, q)
    mm, md = ref.mm, ref.md
    for j in range(1, desc.model.njoints):
        bodies = [
            b
            for b in range(1, mm.nbody)
            if desc.model.frames[
                desc.model.getFrameId(
                    mujoco.mj_id2name(mm, mujoco.mjtObj.mjOBJ_BODY, int(mm.body_weldid[b])), pin.FrameType.BODY
                )
            ].parentJoint
            == j
        ]
        if not bodies:
            continue
        mass = sum(mm.body_mass[b] for b in bodies)
        ours = data.oMi[j].act(desc.model.inertias[j])
        assert float(ours.mass) == pytest.approx(mass, rel=1e-12)
        if mass == 0:
            continue
        com = sum(mm.body_mass[b] * md.xipos[b] for b in bodies) / mass
        inertia = sum(
            md.ximat[b].reshape(3, 3) @ np.diag(mm.body_inertia[b]) @ md.ximat[b].reshape(3, 3).T
            + mm.body_mass[b]
            * (
                np.dot(md.xipos[b] - com, md.xipos[b] - com) * np.eye(3)
                - np.outer(md.xipos[b] - com, md.xipos[b] - com)
            )
            for b in bodies
        )
        np.testing.assert_allclose(ours.lever, com, atol=1e-12)
        np.testing.assert_allclose(ours.inertia, inertia, atol=1e-12 * max(1e-6, np.max(np.abs(inertia))))


def test_what_the_reader_finds_in_the_menagerie_files():
    cassie, gripper = read_mjcf(CASSIE), read_mjcf(GRIPPER)
    assert cassie.urdf is None and gripper.urdf is not None  # ball and free joints: no URDF tree
    assert [c.kind for c in cassie.closures] == ["spherical"] * 4 and not cassie.couplings and not cassie.actuators
    assert cassie.actuated == tuple(
        f"{s}-{j}" for s in ("left", "right") for j in ("hip-roll", "hip-yaw", "hip-pitch", "knee", "foot")
    )
    stiff = {s.joint: (s.stiffness, s.reference) for s in cassie.springs if s.stiffness}
    assert stiff == {
        "left-shin": (1500.0, 0.0),
        "left-heel-spring": (1250.0, 0.0),
        "right-shin": (1500.0, 0.0),
        "right-heel-spring": (1250.0, 0.0),
    }
    assert {s.joint: s.damping for s in cassie.springs}["left-achilles-rod"] == 0.01  # a ball joint's damper
    assert cassie.model.joints[1].shortname() == "JointModelFreeFlyer"
    assert [c.kind for c in gripper.closures] == ["spherical"] * 2
    (coupling,) = gripper.couplings
    assert (coupling.follower, coupling.leader, coupling.polynomial[:2]) == (
        (("right_driver_joint", 1.0),),
        (("left_driver_joint", 1.0),),
        (0.0, 1.0),
    )
    (tendon,) = gripper.actuators
    assert gripper.actuated == ("fingers_actuator",)
    assert tendon.joints == (("right_driver_joint", 0.5), ("left_driver_joint", 0.5))
    assert {s.joint: (s.stiffness, s.reference) for s in gripper.springs if s.stiffness} == {
        "right_spring_link_joint": (0.05, 2.62),
        "left_spring_link_joint": (0.05, 2.62),
    }


@pytest.mark.parametrize("robot", ["cassie-fixed", "cassie-floating", "2f85"])
def test_dof_closure_and_holding_efforts_agree_with_mujoco(robot, tmp_path):
    """DOF, closure residual, gravity and springs, and the holding efforts, ours and MuJoCo's, to 1e-8."""
    path = {"cassie-fixed": _fixed_cassie(tmp_path), "cassie-floating": CASSIE, "2f85": GRIPPER}[robot]
    desc = read_mjcf(path)
    held = STOPS if robot == "2f85" else ()
    st, ref = Statics(desc, held), MujocoReference(path, desc.model)
    if robot == "2f85":
        q = st.assemble(st.configuration(desc.guess), {**{s: 0.0 for s in STOPS}, "right_driver_joint": 0.4})
    elif robot == "cassie-fixed":
        q = _cassie_pose(desc, st)
    else:  # the fixed robot's settled legs under a floating pelvis
        fixed = read_mjcf(_fixed_cassie(tmp_path))
        settled = _cassie_pose(fixed, Statics(fixed))
        q = st.configuration(desc.guess)
        for j in range(1, fixed.model.njoints):
            mine, theirs = desc.model.joints[desc.model.getJointId(fixed.model.names[j])], fixed.model.joints[j]
            q[mine.idx_q : mine.idx_q + mine.nq] = settled[theirs.idx_q : theirs.idx_q + theirs.nq]
    mj = ref.at(q)
    assert np.max(np.abs(mj["residual"])) < TOL
    dof = {"cassie-fixed": 16, "cassie-floating": 22, "2f85": 3}[robot]
    assert st.mobility(q) == dof == desc.model.nv - np.linalg.matrix_rank(mj["J"], 1e-9 * np.max(np.abs(mj["J"])))
    g = st.generalised(q)
    np.testing.assert_allclose(g, mj["generalised"], atol=TOL * max(1.0, np.max(np.abs(g))))
    u, left = st.efforts(q)
    u_mj, left_mj = ref.efforts(q, held)
    np.testing.assert_allclose(u, ref.in_our_units(u_mj), atol=TOL * max(1.0, np.max(np.abs(u))))
    assert left == pytest.approx(left_mj, rel=TOL, abs=TOL)
    if robot == "cassie-floating":  # nothing holds the whole robot's weight: the pelvis rows carry it
        weight = sum(float(i.mass) for i in desc.model.inertias) * np.linalg.norm(desc.model.gravity.linear)
        assert np.linalg.norm(g[:3]) == pytest.approx(weight, rel=1e-12) and left >= weight * (1 - 1e-12)
    else:
        assert left < TOL and (robot != "2f85" or np.all(u[1:] < 0))  # the stops push back into their range
    idle = {"2f85": {}}.get(robot, {"left-achilles-rod": 1, "right-achilles-rod": 1})
    assert st.idle(q) == idle  # Cassie's achilles rods spin between two balls


SYNTHETIC = """<mujoco model="kinds">
  <compiler angle="radian"/>
  <default><geom type="capsule" size="0.01" density="2700"/></default>
  <worldbody>
    <body name="A" pos="0 0 0.2"><joint name="a1" axis="0 1 0" ref="0.2" stiffness="3" springref="0.5" damping="0.1"/>
      <geom fromto="0 0 0 0.3 0 0"/><site name="sA" pos="0.3 0 0" euler="0.3 0 0"/>
      <body name="A2" pos="0.3 0 0"><joint name="a2" axis="1 0 0"/><geom fromto="0 0 0 0 0.2 0"/>
        <site name="sA2" pos="0 0.2 0"/></body></body>
    <body name="W" pos="0.5 0 0.5"><freejoint name="w"/><geom size="0.05" type="sphere"/></body>
    <body name="U" pos="0.2 0.3 0.1" euler="0.2 0 0"><freejoint name="u"/><geom size="0.05" type="sphere"/></body>
    <body name="V" pos="0.3 0.1 0.2" euler="0 0.4 0"><freejoint name="v"/><geom size="0.05" type="sphere"/>
      <site name="sV" pos="0.1 0 0"/></body>
    <body name="P" pos="0.3 0.2 -0.3"><joint name="p" type="ball" pos="0 0 0.1"/><geom fromto="0 0 0.1 0 0 0.5"/>
      <site name="sP" pos="0 0 0.5"/></body>
    <body name="C" pos="1 0 0"><joint name="c1" axis="0 0 1" ref="0.3"/><joint name="c2" type="slide" axis="1 0 0"
        ref="0.05" stiffness="40" springref="0.1"/><geom fromto="0 0 0 0.2 0 0"/></body>
    <body name="D" pos="1 1 0"><joint name="c3" axis="0 0 1" armature="0.02"/><geom fromto="0 0 0 0.2 0 0"/>
      <body name="E" pos="0.2 0 0"><joint name="c4" axis="0 0 1"/><geom fromto="0 0 0 0.2 0 0"/>
        <body name="G" pos="0.2 0 0"><joint name="c5" axis="0 0 1"/><geom fromto="0 0 0 0.2 0 0"/></body></body></body>
  </worldbody>
  <tendon><fixed name="t1"><joint joint="c3" coef="2"/><joint joint="c4" coef="-1"/></fixed>
    <fixed name="t2"><joint joint="c5" coef="0.5"/></fixed></tendon>
  <equality>
    <weld name="relpose" body1="A" body2="W" anchor="0.1 0 0" relpose="0.4 0.1 0.2 0.9 0.1 0.3 0"/>
    <weld name="at_qpos0" body1="A2" body2="U" anchor="0 0.1 0.05"/>
    <weld name="sites" site1="sV" site2="sA"/>
    <connect name="ball" site1="sP" site2="sA2"/>
    <joint name="poly" joint1="c1" joint2="c2" polycoef="0.1 2 -3 0.5 0"/>
    <tendon name="lengths" tendon1="t1" tendon2="t2" polycoef="0.05 1.5 0.3 0 0"/>
  </equality>
  <actuator><motor name="m_t1" tendon="t1" gear="2"/><motor name="m_a1" joint="a1" gear="3"/></actuator>
</mujoco>
"""


@pytest.mark.parametrize(
    "flags",
    ["", '<option><flag gravity="disable" spring="disable"/></option>'],
    ids=["as-written", "no-gravity-no-springs"],
)
def test_every_equality_kind_tendon_spring_and_armature_agree_with_mujoco(flags, tmp_path):
    """Welds (explicit relpose, sites), a site connect, a polynomial joint equality, a tendon equality,
    a tendon actuator, springs on a hinge and a slide, armature: at random configurations the
    coupling residuals equal MuJoCo's rows, the actuation matrix its moments, gravity and springs its
    forces; closed by our rows, MuJoCo's equality residuals vanish and the DOF agree. Also with gravity
    and springs switched off by MuJoCo's flags."""
    path = tmp_path / "kinds.xml"
    path.write_text(SYNTHETIC.replace('<compiler angle="radian"/>', '<compiler angle="radian"/>' + flags))
    desc = read_mjcf(path)
    st, ref = Statics(desc), MujocoReference(path, desc.model)
    rng = np.random.default_rng(3)
    eq_id = {mujoco.mj_id2name(ref.mm, mujoco.mjtObj.mjOBJ_EQUALITY, e): e for e in range(ref.mm.neq)}
    for _ in range(5):
        q = pin.integrate(desc.model, st.configuration(desc.guess), rng.normal(scale=0.7, size=desc.model.nv))
        mj = ref.at(q)
        residual, _ = st.rows(q)
        ids = ref.md.efc_id[: ref.md.nefc][ref.md.efc_type[: ref.md.nefc] == mujoco.mjtConstraint.mjCNSTR_EQUALITY]
        for k, coupling in enumerate(desc.couplings):
            assert residual[-len(desc.couplings) + k] == pytest.approx(
                mj["residual"][ids == eq_id[coupling.name]][0], abs=1e-12
            )
        np.testing.assert_allclose(st.S * ref.in_our_units(np.ones(2)), mj["moment"].T, atol=1e-12)
        np.testing.assert_allclose(st.generalised(q), mj["generalised"], atol=1e-10)
    armature = np.zeros(desc.model.nv)
    armature[desc.model.joints[desc.model.getJointId("c3")].idx_v] = 0.02
    np.testing.assert_array_equal(desc.model.armature, armature)
    q = st.assemble(st.configuration(desc.guess), {"c2": 0.08, "c5": 0.4, "a1": 0.3})
    mj = ref.at(q)
    assert np.max(np.abs(mj["residual"])) < 1e-10
    assert st.mobility(q) == desc.model.nv - np.linalg.matrix_rank(mj["J"], 1e-9 * np.max(np.abs(mj["J"])))


@pytest.mark.parametrize("path", [FIXTURES / "rssr.xml", GRIPPER], ids=["rssr", "2f85"])
def test_the_urdf_text_builds_the_readers_model(path):
    """Where URDF holds the tree, Pinocchio's URDF parser on `desc.urdf` gives the reader's model:
    the same joints, and every frame of the reader's model at the same place at random q."""
    desc = read_mjcf(path)
    other = build_model(desc.urdf)
    assert sorted(other.names) == sorted(desc.model.names)
    rng = np.random.default_rng(0)
    for _ in range(3):
        values = {desc.model.names[j]: rng.uniform(-1, 1) for j in range(1, desc.model.njoints)}
        q1, q2 = (np.array([values[m.names[j]] for j in range(1, m.njoints)]) for m in (desc.model, other))
        d1, d2 = desc.model.createData(), other.createData()
        pin.framesForwardKinematics(desc.model, d1, q1)
        pin.framesForwardKinematics(other, d2, q2)
        for i, frame in enumerate(desc.model.frames):
            if frame.type in (pin.FrameType.BODY, pin.FrameType.OP_FRAME):
                there = d2.oMf[other.getFrameId(frame.name, pin.FrameType.BODY)]
                np.testing.assert_allclose(d1.oMf[i].homogeneous, there.homogeneous, atol=1e-12)
        for j in range(1, desc.model.njoints):
            k = other.getJointId(desc.model.names[j])
            np.testing.assert_allclose(
                d1.oMi[j].act(desc.model.inertias[j]).matrix(), d2.oMi[k].act(other.inertias[k]).matrix(), atol=1e-12
            )


BASE = (
    '<mujoco><worldbody><body name="b"><joint name="h" axis="0 0 1"/><geom size="0.1"/><site name="s"/>'
    '<body name="c" pos="1 0 0"><joint name="k" type="ball"/><geom size="0.1"/><site name="s2"/></body>'
    "</body></worldbody>{}</mujoco>"
)
MALFORMED = {  # file text -> what the one-line error says
    "": "empty",
    "<mujoco><worldbody>": "not well-formed",
    "<robot/>": "starts with <mujoco>",
    "<mujoco><worldbody><body><geom size='1'/></body></worldbody></mujoco>": "no joint",
    BASE.format(
        '<tendon><fixed name="t"><joint joint="nope" coef="1"/></fixed></tendon>'
    ): "joint 'nope' not found in tendon",
    BASE.format('<equality><joint joint1="nope"/></equality>'): "unknown element 'nope' in equality",
    BASE.replace('type="ball"', 'type="screw"'): "invalid keyword: 'screw'",
    BASE.format('<equality><connect body1="b" body2="b" anchor="0 0 0"/></equality>'): "repeated in equality",
    BASE.format('<equality><joint joint1="k" joint2="h"/></equality>'): "only HINGE and SLIDE joint allowed",
    BASE.replace('type="ball"', 'type="ball" stiffness="2"'): "ball or free joint's stiffness",
    BASE.replace('<body name="b">', '<body name="b" gravcomp="1">'): "gravity compensation",
    BASE.format(
        '<tendon><fixed name="t" stiffness="5"><joint joint="h" coef="1"/></fixed></tendon>'
    ): "stiffness on a tendon",
    BASE.format(
        '<tendon><spatial name="t"><site site="s"/><site site="s2"/></spatial></tendon>'
        '<actuator><general name="m" tendon="t" dyntype="filter" dynprm="1"/></actuator>'
    ): "only fixed-gain actuators without dynamics",
    BASE.format(
        '<tendon><fixed name="t"><joint joint="h" coef="1"/></fixed></tendon>'
        '<actuator><motor name="h" tendon="t"/></actuator>'
    ): "tendon actuator named like a joint",
    BASE.format('<actuator><motor name="m1" joint="h"/><motor name="m2" joint="h"/></actuator>'): "driven by another",
    BASE.format('<actuator><motor name="m" site="s"/></actuator>'): "acts on a site",
    BASE.format('<actuator><motor name="m" joint="k" gear="1 0 0 0 0 0"/></actuator>'): "drives the ball or free joint",
}


@pytest.mark.parametrize("text, needle", MALFORMED.items(), ids=[f"m{i}" for i in range(len(MALFORMED))])
def test_malformed_mjcf_is_refused_in_one_line_naming_the_element(text, needle, tmp_path):
    """The reader's error, and the same one line from `mechkit report` (exit 2, no traceback)."""
    path = tmp_path / "broken.xml"
    path.write_text(text)
    with pytest.raises(MalformedDescription, match=re.escape(needle)) as err:
        read_mjcf(path)
    assert refusal(path) == f"mechkit: error: {err.value}"


@pytest.mark.parametrize("case", ["no joint", "cassie"])
def test_mechkit_report_through_the_command_line(case, tmp_path):
    """A malformed file: one line on stderr, exit 2, no traceback. Cassie (ball and free joints, loops,
    springs): the report, exit 0, its numerical DOF the Kutzbach count, its idle rods named."""
    path = CASSIE
    if case == "no joint":
        path = tmp_path / "none.xml"
        path.write_text(next(t for t, n in MALFORMED.items() if n == case))
    out = subprocess.run(
        [sys.executable, "-m", "mechkit", "report", str(path)], capture_output=True, text=True, check=False
    )
    assert "Traceback" not in out.stderr
    if case == "no joint":
        lines = out.stderr.strip().splitlines()
        assert out.returncode == 2 and len(lines) == 1 and case in lines[0]
    else:
        assert out.returncode == 0, out.stderr
        assert "DOF numerical 22, Gruebler 22" in out.stdout
        assert "left-achilles-rod 1, right-achilles-rod 1" in out.stdout


def test_a_ball_joint_loads_as_the_three_hinges_do():
    """The RSSR fixture writes its ball as three hinges; written as a ball it loads (the core takes any
    joint) with the same mobility and the same assembly of its crank and rocker."""
    rssr = (FIXTURES / "rssr.xml").read_text()
    ball = (
        rssr.replace('type="hinge" axis="1 0 0"/>', 'type="ball"/>')
        .replace('<joint name="By" type="hinge" axis="0 1 0"/>', "")
        .replace('<joint name="Bz" type="hinge" axis="0 0 1"/>', "")
    )
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "rssr_ball.xml"
        path.write_text(ball)
        m_ball = mechkit.load(path)
    m_hinges = mechkit.load(FIXTURES / "rssr.xml")
    assert m_ball.model.nq == m_hinges.model.nq + 1 and m_ball.model.nv == m_hinges.model.nv
    assert m_ball.mobility().dof == m_hinges.mobility().dof
    for joint in m_hinges.actuated:
        assert m_ball.home_q[m_ball.q_index(joint)] == pytest.approx(
            m_hinges.home_q[m_hinges.q_index(joint)], abs=1e-12
        )


def test_mjcf_errors(tmp_path):
    rssr = (FIXTURES / "rssr.xml").read_text()
    cases = {
        rssr.replace('body2="rocker_link"', 'body2="rocker_lnk"'): "MuJoCo could not compile",
        "<robot/>": "starts with <mujoco>",
    }
    for i, (text, needle) in enumerate(cases.items()):
        with pytest.raises(MalformedDescription, match=needle):
            mechkit.load(written(tmp_path, text, f"m{i}.xml"))


ONSHAPE_FOUR_BAR = FIXTURES / "onshape" / "four_bar.xml"


def _anchor_form(text: str) -> str:
    """The four-bar's two site connects as MuJoCo 2's body-and-anchor connects (anchors on the coupler)."""
    for site in ("closing_C_1", "closing_C_1_z"):
        pos = re.search(rf'name="{site}" pos="([^"]+)"', text).group(1)
        text = text.replace(
            f'site1="{site}" site2="{site.replace("_1", "_2")}"', f'body1="coupler" body2="rocker" anchor="{pos}"'
        )
    return text


def _rocker_sites_turned(text: str, angle: float) -> str:
    """The rocker's closing sites turned by `angle` (rad) about its hinge (y): the file opens at qpos0."""
    R = pin.exp3(np.array([0.0, angle, 0.0]))
    for site in ("closing_C_2", "closing_C_2_z"):
        pos = re.search(rf'name="{site}" pos="([^"]+)"', text).group(1)
        turned = " ".join(repr(float(x)) for x in R @ np.array([float(x) for x in pos.split()]))
        text = text.replace(f'name="{site}" pos="{pos}"', f'name="{site}" pos="{turned}"')
    return text


def test_two_site_connects_are_one_hinge_closure_as_the_anchor_form(tmp_path):
    """onshape-to-robot's hinge closure (two `connect`s by site, 0.1 m apart along the hinge) reads as one
    revolute cut, as the same connects written by body and anchor: the Kutzbach count 1 (two balls
    counted -1), the mobility 1 and MuJoCo's (nv - rank of its equality rows), and every frame of the
    two models at the same place at assembled configurations."""
    anchored = written(tmp_path, _anchor_form(ONSHAPE_FOUR_BAR.read_text()), "anchored.xml")
    assert "site1" not in anchored.read_text()
    sites, anchors = read_mjcf(ONSHAPE_FOUR_BAR), read_mjcf(anchored)
    for desc in (sites, anchors):
        assert [c.kind for c in desc.closures] == ["revolute"]
        np.testing.assert_allclose(desc.closures[0].axis, [0.0, 1.0, 0.0], atol=1e-15)
    assert mechkit.load(ONSHAPE_FOUR_BAR).structure.kutzbach == mechkit.load(anchored).structure.kutzbach == 1
    ref = MujocoReference(ONSHAPE_FOUR_BAR, sites.model)
    for crank in (0.0, 0.4, -0.7):
        qs, qa = (Statics(d).assemble(Statics(d).configuration(d.guess), {"crank": crank}) for d in (sites, anchors))
        np.testing.assert_allclose(qs, qa, atol=1e-12)
        J = ref.at(qs)["J"]
        assert np.max(np.abs(ref.at(qs)["residual"])) < 1e-12
        assert Statics(sites).mobility(qs) == 1 == sites.model.nv - np.linalg.matrix_rank(J, 1e-9)
        for d in (sites, anchors):
            pin.framesForwardKinematics(d.model, data := d.model.createData(), qs)
            c = d.closures[0]
            np.testing.assert_allclose(
                data.oMf[d.model.getFrameId(c.frame_a)].translation,
                data.oMf[d.model.getFrameId(c.frame_b)].translation,
                atol=1e-12,
            )


def test_site_connects_open_at_qpos0_are_closed_where_mujoco_closes_them(tmp_path):
    """The rocker's closing sites turned 0.3 rad about its hinge: at qpos0 the connects are open. Where
    Newton on MuJoCo's own equality rows closes them, the reader's hinge cut is closed too (its rows
    vanish), and the mobility there is 1, as nv - rank of MuJoCo's rows."""
    path = written(tmp_path, _rocker_sites_turned(ONSHAPE_FOUR_BAR.read_text(), 0.3), "open.xml")
    desc = read_mjcf(path)
    st, ref = Statics(desc), MujocoReference(path, desc.model)
    q = st.configuration(desc.guess)
    assert np.linalg.norm(ref.at(q)["residual"]) > 0.05 and np.linalg.norm(st.rows(q)[0]) > 0.05
    for _ in range(30):
        mj = ref.at(q)
        q = q - np.linalg.pinv(mj["J"], rcond=1e-12) @ mj["residual"]
    assert np.max(np.abs(ref.at(q)["residual"])) < 1e-13
    assert np.max(np.abs(st.rows(q)[0])) < 1e-12
    assert st.mobility(q) == 1 == desc.model.nv - np.linalg.matrix_rank(ref.at(q)["J"], 1e-9)


def test_site_connects_whose_points_are_unequally_apart_are_refused(tmp_path):
    """Two site connects 0.1 m apart on the coupler and 0.12 m on the rocker: no pose closes both (MuJoCo
    would settle between them); the reader names both equalities."""
    text = ONSHAPE_FOUR_BAR.read_text().replace('<site name="closing_C_2_z" pos="-0.038894251654084 0.1', "@")
    text = text.replace("@", '<site name="closing_C_2_z" pos="-0.038894251654084 0.12')
    with pytest.raises(MalformedDescription, match=r"0\.1 m apart on 'coupler' but 0\.12 m apart on 'rocker'"):
        read_mjcf(written(tmp_path, text, "unequal.xml"))


#: Bricard's orthogonal 6R linkage (ours: links 0.1 m, twists +-90 degrees, no offsets): overconstrained,
#: Kutzbach 5 + 1 - 6 = 0 with a hinge cut (-1 read as two balls), mobile with one freedom.
BRICARD_A, BRICARD_TWISTS = 0.1, (np.pi / 2, -np.pi / 2) * 3


def _bricard_step(i: int, theta: float) -> pin.SE3:
    """Joint i's frame to joint i+1's (Denavit-Hartenberg: turn theta about z, a along x, twist about x)."""
    turn = pin.SE3(pin.exp3(np.array([0.0, 0.0, theta])), np.zeros(3))
    return turn * pin.SE3(pin.exp3(np.array([BRICARD_TWISTS[i], 0.0, 0.0])), np.array([BRICARD_A, 0.0, 0.0]))


def _bricard_closed() -> np.ndarray:
    """Joint angles (6,) closing the loop (the product of the six steps the identity), by Newton."""

    def residual(theta):
        product = pin.SE3.Identity()
        for i, t in enumerate(theta):
            product = product * _bricard_step(i, t)
        return pin.log6(product).vector

    theta = np.array([0.7, 2.0, 0.7, 2.0, 0.7, 2.0])
    for _ in range(30):
        J = np.column_stack([(residual(theta + h) - residual(theta - h)) / 2e-7 for h in 1e-7 * np.eye(6)])
        theta = theta - np.linalg.pinv(J, 1e-9) @ residual(theta)
    assert np.linalg.norm(residual(theta)) < 1e-14
    return theta


def _bricard_mjcf(theta: np.ndarray, closed: np.ndarray, form: str) -> str:
    """The Bricard linkage as MJCF, its five tree joints at 0 where the angles are `theta`, its sixth
    joint (link 5 to the ground) cut as two connects 0.1 m apart on its axis, on the ground where
    `closed` puts it: by site, or by body and anchor (on link 5)."""
    quat = lambda R: " ".join(repr(float(c)) for c in pin.Quaternion(R).coeffs()[[3, 0, 1, 2]])
    vec = lambda v: " ".join(repr(float(c)) for c in v)
    body = ""
    for i in range(5):
        place = pin.SE3(pin.exp3(np.array([0.0, 0.0, theta[0]])), np.zeros(3)) if i == 0 else _bricard_step(i - 1, 0.0)
        if i > 0:
            place = place * pin.SE3(pin.exp3(np.array([0.0, 0.0, theta[i]])), np.zeros(3))
        body += (
            f'<body name="L{i + 1}" pos="{vec(place.translation)}" quat="{quat(place.rotation)}">'
            f'<joint name="j{i + 1}" axis="0 0 1"/><geom fromto="0 0 0 {BRICARD_A} 0 0"/>'
        )
    six = _bricard_step(4, 0.0)  # joint 6's frame on link 5
    ground = (_bricard_step(5, closed[5])).inverse()  # joint 6's frame on the ground when closed
    ends = [
        (six.translation + s * six.rotation[:, 2], ground.translation + s * ground.rotation[:, 2]) for s in (0, 0.1)
    ]
    sites = "".join(f'<site name="on5_{k}" pos="{vec(p)}"/>' for k, (p, _) in enumerate(ends))
    world = "".join(f'<site name="on0_{k}" pos="{vec(g)}"/>' for k, (_, g) in enumerate(ends))
    if form == "site":
        equality = "".join(f'<connect site1="on5_{k}" site2="on0_{k}"/>' for k in range(2))
    else:
        equality = "".join(f'<connect body1="L5" body2="world" anchor="{vec(p)}"/>' for p, _ in ends)
    return (
        '<mujoco model="bricard"><default><geom type="capsule" size="0.005" density="2700"/></default>'
        f"<worldbody>{world}{body}{sites}{'</body>' * 5}</worldbody><equality>{equality}</equality></mujoco>"
    )


def test_bricards_linkage_cut_by_two_site_connects_is_one_hinge_with_one_freedom(tmp_path):
    """Bricard's overconstrained 6R loop, its sixth hinge cut as two connects by site or by anchor: one
    revolute cut either way, the Kutzbach count 0 (two balls counted -1), the numerical mobility 1 as
    MuJoCo's (nv - rank of its equality rows), and both forms assemble to the same configuration."""
    closed = _bricard_closed()
    descs = [read_mjcf(written(tmp_path, _bricard_mjcf(closed, closed, f), f"{f}.xml")) for f in ("site", "anchor")]
    for form, desc in zip(("site", "anchor"), descs, strict=True):
        assert [c.kind for c in desc.closures] == ["revolute"]
        assert mechkit.load(tmp_path / f"{form}.xml").structure.kutzbach == 0
    ref = MujocoReference(tmp_path / "site.xml", descs[0].model)
    for move in (0.0, 0.2, -0.3):
        qs = [Statics(d).assemble(Statics(d).configuration(d.guess), {"j1": move}) for d in descs]
        np.testing.assert_allclose(qs[0], qs[1], atol=1e-12)
        mj = ref.at(qs[0])
        assert np.max(np.abs(mj["residual"])) < 1e-12
        assert Statics(descs[0]).mobility(qs[0]) == 1 == 5 - np.linalg.matrix_rank(mj["J"], 1e-9)


def test_bricards_site_connects_written_open_close_where_mujoco_closes_them(tmp_path):
    """The same linkage written at other angles (qpos0 open: link 5's hinge line off the ground's, in
    place and direction): where Newton on MuJoCo's own rows closes the connects, the reader's hinge cut
    (frame b turned onto the ground's line) is closed too, and the mobility there is MuJoCo's, 1."""
    closed = _bricard_closed()
    path = written(tmp_path, _bricard_mjcf(closed + np.array([0.1, -0.05, 0.08, 0.0, 0.06, 0.0]), closed, "site"))
    desc = read_mjcf(path)
    st, ref = Statics(desc), MujocoReference(path, desc.model)
    q = st.configuration(desc.guess)
    assert np.linalg.norm(ref.at(q)["residual"]) > 0.01
    for _ in range(40):
        mj = ref.at(q)
        q = q - np.linalg.pinv(mj["J"], rcond=1e-10) @ mj["residual"]
    assert np.max(np.abs(ref.at(q)["residual"])) < 1e-13
    assert np.max(np.abs(st.rows(q)[0])) < 1e-12
    assert st.mobility(q) == 1 == 5 - np.linalg.matrix_rank(ref.at(q)["J"], 1e-9)


def test_two_site_connects_naming_the_bodies_in_either_order_are_one_hinge(tmp_path):
    """The four-bar's second connect written rocker first (site1 on the rocker): still one revolute cut,
    closed at qpos0, about the hinge (y)."""
    text = ONSHAPE_FOUR_BAR.read_text().replace(
        'site1="closing_C_1_z" site2="closing_C_2_z"', 'site1="closing_C_2_z" site2="closing_C_1_z"'
    )
    desc = read_mjcf(written(tmp_path, text, "swapped.xml"))
    assert [c.kind for c in desc.closures] == ["revolute"]
    np.testing.assert_allclose(desc.closures[0].axis, [0.0, 1.0, 0.0], atol=1e-15)
    assert np.max(np.abs(Statics(desc).rows(Statics(desc).configuration(desc.guess))[0])) < 1e-15
