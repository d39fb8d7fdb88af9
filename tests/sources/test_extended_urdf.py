"""`mechkit.sources.extended_urdf`: a bad YAML sidecar is a named error.

Extended URDF (mechkit.sources.extended_urdf) on the field's own files: every robot of Gepetto's
example-parallel-robots, against a model built from the same raw files the way Gepetto's loader builds
it (`independent.gepetto_load`), then DOF, idle freedoms and holding torques by an independent
computation (`independent.study`) on both. One test per robot, so one failure hides no other.
"""

from __future__ import annotations

import functools
import subprocess
import sys
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from tests_support import FIXTURES

import mechkit
from mechkit.base.exceptions import MalformedDescription
from mechkit.cli import main
from mechkit.core.records import Coupling
from mechkit.sources import read
from mechkit.sources.extended_urdf import read_extended_urdf, sidecar_of

from .independent import Cut, LoopsDoNotClose, cuts_of, gepetto_load, require_closed, study, urdf_mimics


def test_sidecar_errors(tmp_path):
    tree = (FIXTURES / "leg.urdf").read_text()
    cases = {
        "closed_loop: [[rod1_tip, shank_levr]]\ntype: [3d]\nname_mot: [hip]\n": "shank_levr",
        "closed_loop: [[rod1_tip, shank_lever]]\ntype: [3d]\nname_mot: [hip, kne]\n": "kne",
        "closed_loop: [[rod1_tip, shank_lever]]\ntype: [4d]\nname_mot: [hip]\n": "4d",
        "closed_loop: [[rod1_tip, shank_lever]]\ntype: [3d, 6d]\nname_mot: [hip]\n": "one type per",
        "closed_loop: [[rod1_tip, rod1]]\ntype: [3d]\nname_mot: [hip]\n": "one body",
        "closed_loop: [rod1_tip\n": "not YAML",
        "name_mot: [hip]\n": "closed_loop",
    }
    for i, (sidecar, needle) in enumerate(cases.items()):
        folder = tmp_path / str(i)
        folder.mkdir()
        (folder / "leg.urdf").write_text(tree)
        (folder / "leg.yaml").write_text(sidecar)
        with pytest.raises(MalformedDescription, match=needle):
            mechkit.load(folder / "leg.urdf")


GEPETTO = Path(__file__).parent.parent / "fixtures" / "field" / "gepetto"
ROBOTS = sorted(p.name for p in GEPETTO.iterdir() if p.is_dir())
#: robot -> (cuts, numerical DOF, undriven freedoms, motors hold gravity at rest), fixed base, at the
#: configuration each closes to from the neutral one. The undriven freedoms are the motions no motor
#: drives: rods spinning about their own axis between two balls (and, on the 5-bar, the two end spheres
#: spinning together), which are idle freedoms; wl16_like's six legs spinning about their axes (each a
#: cylinder and a piston on a prismatic, two bodies: not idle in the sense of moving one body alone);
#: disney_like's ankle rod turning about a revolute that misses its ball's centre by 0.3 mm (it moves
#: the leg by 1e-4 of its turn: not idle). Where gravity loads one of them (a rod's centre of mass off
#: its axis), the motors cannot hold there (test_field_gepetto: they hold once it has settled).
FACTS = {
    "5bar_linkage": (1, 3, 1, True),
    "5bar_linkage_iso3d": (1, 2, 0, True),
    "5bar_linkage_iso6d": (1, 2, 0, True),
    "battobot_6d": (6, 12, 0, True),
    "cassie_like": (2, 7, 2, True),
    "digit_like": (3, 9, 3, True),
    "digit_like_2legs": (6, 12, 0, True),
    "digit_like_2legs_6D": (6, 12, 0, True),
    "digit_like_2legs_old": (6, 12, 0, True),
    "disney_like": (3, 9, 3, False),
    "robot_delta": (3, 5, 3, True),
    "talos_like": (1, 7, 1, False),
    "true_talos_2_legs": (2, 34, 2, True),
    "wl16_like": (5, 12, 6, False),
}
#: Published loops that do not close (best frame errors over many starts: m, rad mixed as in `study`).
UNCLOSABLE = {"kangaroo_like": (0.07, 0.09), "kangaroo_like_2legs": (0.035, 0.045)}
#: Gepetto's `robot_options`: these load on a free-flyer by default.
FREE_FLYING = ("battobot_6d", "digit_like_2legs", "digit_like_2legs_6D", "disney_like", "true_talos_2_legs")


def _urdf(robot: str) -> Path:
    return next((GEPETTO / robot).glob("*.urdf"))


@functools.cache
def _ours(robot: str, freeflyer: bool = False):
    urdf = _urdf(robot)
    return read_extended_urdf(urdf, sidecar_of(urdf), freeflyer=freeflyer)


@functools.cache
def _gepettos(robot: str, freeflyer: bool = False) -> tuple[pin.Model, list[Cut], list[str]]:
    return gepetto_load(_urdf(robot), GEPETTO / robot / "robot.yaml", freeflyer)


def _mimics(robot: str) -> list[Coupling]:
    return urdf_mimics(_urdf(robot))


def _frames(model: pin.Model) -> list[tuple]:
    return sorted(
        (f.name, str(f.type), model.names[f.parentJoint], tuple(np.round(f.placement.homogeneous.ravel(), 12)))
        for f in model.frames
        if f.name != "universe"
    )


@pytest.mark.parametrize(
    "robot, freeflyer", [(r, False) for r in ROBOTS if r != "disney_robot"] + [(r, True) for r in FREE_FLYING]
)
def test_the_reader_builds_the_model_gepettos_loader_builds(robot, freeflyer):
    """Same joints (names, types, parents, placements), same bodies, same frames, same motors."""
    ours, (theirs, _, motors) = _ours(robot, freeflyer).model, _gepettos(robot, freeflyer)
    assert list(ours.names) == list(theirs.names)
    assert [j.shortname() for j in ours.joints] == [j.shortname() for j in theirs.joints]
    assert list(ours.parents) == list(theirs.parents)
    for j in range(1, ours.njoints):  # the universe's inertia is the root link's in ours, zero in theirs
        assert ours.jointPlacements[j].isApprox(theirs.jointPlacements[j], 1e-12)
        np.testing.assert_allclose(ours.inertias[j].matrix(), theirs.inertias[j].matrix(), rtol=0, atol=1e-12)
    assert _frames(ours) == _frames(theirs)
    assert sorted(_ours(robot, freeflyer).actuated) == sorted(motors)


@pytest.mark.parametrize("robot", sorted(FACTS))
def test_dof_idle_freedoms_and_holding_torques_agree_with_gepettos_model(robot):
    """Closed by damped least squares on each model: the same DOF, the same undriven freedoms, and where
    the motors hold, the same torques to 1e-8 (both with the URDF's mimic rows)."""
    desc = _ours(robot)
    theirs, their_cuts, motors = _gepettos(robot)
    cuts = cuts_of(desc.model, desc.closures)
    found = study(desc.model, cuts, list(desc.actuated), couplings=desc.couplings)
    ref = study(theirs, their_cuts, motors, couplings=_mimics(robot))
    require_closed(robot, desc.model, cuts, found.q)
    require_closed(robot, theirs, their_cuts, ref.q)
    assert list(desc.couplings) == _mimics(robot)
    n_cuts, dof, undriven, holds = FACTS[robot]
    assert (len(desc.closures), found.dof, found.undriven, found.holds) == (n_cuts, dof, undriven, holds)
    assert (ref.dof, ref.undriven, ref.holds) == (dof, undriven, holds)
    if holds and found.torques_unique:
        scale = max(1.0, max(abs(t) for t in ref.torques.values()))
        assert max(abs(found.torques[m] - ref.torques[m]) for m in motors) <= 1e-8 * scale
    else:  # undetermined or not held: the least-squares answers are not compared, the facts are
        assert robot in ("disney_like", "talos_like", "wl16_like", "true_talos_2_legs")


def test_the_talos_grippers_mimics_are_rows_gepettos_loader_ignores():
    """12 mimic rows: with them the pair has 34 freedoms; Gepetto's model, without, 46."""
    theirs, their_cuts, motors = _gepettos("true_talos_2_legs")
    assert len(_ours("true_talos_2_legs").couplings) == 12
    assert study(theirs, their_cuts, motors).dof == 46


@pytest.mark.parametrize("robot", sorted(UNCLOSABLE))
def test_loops_that_cannot_close_are_refused_by_name_with_the_residual(robot):
    """The Kangaroo files: both readings agree (same model), and no configuration closes them."""
    low, high = UNCLOSABLE[robot]
    desc = _ours(robot)
    for model, cuts in ((desc.model, cuts_of(desc.model, desc.closures)), _gepettos(robot)[:2]):
        found = study(model, cuts, [])
        with pytest.raises(LoopsDoNotClose, match=robot) as err:
            require_closed(robot, model, cuts, found.q)
        assert low < err.value.residual < high and not found.closed


def test_a_misspelt_substitution_is_refused_where_gepettos_loader_keeps_the_revolute():
    """disney_robot's sidecar substitutes 'left_spherical_free_foot'; the URDF spells the joint with a
    circumflex. Gepetto's loader ignores the line: its left foot keeps a revolute where the right has a
    ball, so its two legs differ (14 freedoms, not the mirror images' count)."""
    with pytest.raises(
        MalformedDescription,
        match="'left_spherical_free_foot' is not a joint of robot.urdf \\(closest: 'left_sĥerical_free_foot'\\)",
    ):
        _ours("disney_robot")
    theirs, cuts, motors = _gepettos("disney_robot")
    kinds = {
        n: theirs.joints[theirs.getJointId(n)].shortname() for n in ("spherical_free_foot", "left_sĥerical_free_foot")
    }
    assert kinds == {"spherical_free_foot": "JointModelSpherical", "left_sĥerical_free_foot": "JointModelRZ"}
    assert study(theirs, cuts, motors).dof == 14


@pytest.mark.parametrize("robot", FREE_FLYING)
def test_a_free_flyer_root_adds_six_freedoms_the_motors_cannot_hold(robot):
    desc = _ours(robot, True)
    assert desc.urdf is None and desc.model.joints[1].shortname() == "JointModelFreeFlyer"
    found = study(desc.model, cuts_of(desc.model, desc.closures), list(desc.actuated), couplings=desc.couplings)
    assert found.dof == FACTS[robot][1] + 6 and not found.holds


def _as_three_revolutes(balls: pin.Model, kept: pin.Model, q: np.ndarray) -> np.ndarray:
    """A configuration of the ball model on the three-revolute model: each ball `<x>_rev2` as the angles
    of `<x>_rev0`, `_rev1`, `_rev2` about X, Y, Z (no offset between them in these files), the rest copied."""
    out = pin.neutral(kept)
    for j in range(1, balls.njoints):
        name, jm = balls.names[j], balls.joints[j]
        if jm.shortname() != "JointModelSpherical":
            out[kept.joints[kept.getJointId(name)].idx_q] = q[jm.idx_q]
            continue
        R = pin.Quaternion(q[jm.idx_q : jm.idx_q + 4]).matrix()  # = Rx(a) Ry(b) Rz(c)
        angles = (np.arctan2(-R[1, 2], R[2, 2]), np.arcsin(R[0, 2]), np.arctan2(-R[0, 1], R[0, 0]))
        for k, angle in enumerate(angles):
            out[kept.joints[kept.getJointId(name[:-1] + str(k))].idx_q] = angle
    return out


def test_the_three_revolutes_kept_are_the_same_mechanism_as_gepettos_balls():
    """cassie_like, read with balls=False: the URDF's tree and text; at the configuration the ball model
    (what mechkit.load reads, as Gepetto's loader does) closed, written in three angles per ball, the
    loops are closed and the motors hold with the same torques."""
    urdf = _urdf("cassie_like")
    kept, balls = read_extended_urdf(urdf, sidecar_of(urdf), balls=False), _ours("cassie_like")
    assert kept.urdf is not None and balls.urdf is None
    assert kept.model.njoints == balls.model.njoints + 8 and read(urdf).model.njoints == balls.model.njoints
    ball = study(balls.model, cuts_of(balls.model, balls.closures), list(balls.actuated))
    q = _as_three_revolutes(balls.model, kept.model, ball.q)
    cuts = cuts_of(kept.model, kept.closures)
    require_closed("cassie_like", kept.model, cuts, q, tol=1e-12)
    three = study(kept.model, cuts, list(kept.actuated), q)
    assert three.closed and (three.dof, three.undriven, three.holds) == (ball.dof, ball.undriven, ball.holds)
    for motor in kept.actuated:
        assert three.torques[motor] == pytest.approx(ball.torques[motor], abs=1e-8 * max(1.0, abs(ball.torques[motor])))


def _case(robot: str, sidecar: dict[str, str] | None = None, urdf: dict[str, str] | None = None):
    """A Gepetto robot with its sidecar and URDF texts edited (old -> new, each old must be there)."""
    texts = {"robot.yaml": (GEPETTO / robot / "robot.yaml").read_text(), "robot.urdf": _urdf(robot).read_text()}
    for name, edits in (("robot.yaml", sidecar or {}), ("robot.urdf", urdf or {})):
        for old, new in edits.items():
            assert old in texts[name], (robot, old)
            texts[name] = texts[name].replace(old, new)
    return texts


#: Broken files in the style of the field's: each is a real robot with one realistic slip.
MALFORMED = {
    "a pair naming a frame the URDF lacks": (
        _case("cassie_like", {"'closedloop2_B'": "'closedloop2_C'"}),
        "frame 'closedloop2_C' is not a frame of robot.urdf",
    ),
    "a substitution naming a joint the URDF lacks": (
        _case("disney_robot"),
        "'left_spherical_free_foot' is not a joint",
    ),
    "an unknown joint_type": (
        _case(
            "digit_like_2legs",
            {
                (
                    '    "SPHERICAL",\n    "SPHERICAL",\n    "SPHERICAL",\n'
                    '    "SPHERICAL",\n    "SPHERICAL",\n    "SPHERICAL",'
                ): (
                    '    "BALL",\n    "SPHERICAL",\n    "SPHERICAL",\n'
                    '    "SPHERICAL",\n    "SPHERICAL",\n    "SPHERICAL",'
                )
            },
        ),
        "'BALL' (for joint 'spherical_free_hip') is not one of",
    ),
    "a U-joint about one axis twice": (
        _case("battobot_6d", {'"UJOINT_YZ",\n    "UJOINT_YZ",': '"UJOINT_YY",\n    "UJOINT_YZ",'}),
        "'UJOINT_YY' (for joint 'free_knee_left') is not one of",
    ),
    "joint_type shorter than joint_name": (
        _case("disney_robot", {"'SPHERICAL','SPHERICAL', 'SPHERICAL'": "'SPHERICAL', 'SPHERICAL'"}),
        "needs one type per joint_name: 9 types for 10 joints",
    ),
    "a substitution of a fixed joint": (
        _case(
            "digit_like_2legs_6D", {"joint_name: ['foot_part_toe_b_1/2_2_rev2'": "joint_name: ['closedloop1_A_frame'"}
        ),
        "'closedloop1_A_frame' is a fixed joint of the URDF",
    ),
    "a substitution of a link": (
        _case("digit_like_2legs_6D", {"joint_name: ['foot_part_toe_b_1/2_2_rev2'": "joint_name: ['closedloop1_A'"}),
        "'closedloop1_A' is a link of robot.urdf, not a joint",
    ),
    "a joint substituted twice": (
        _case(
            "disney_like",
            {"name_mot:": "joint_name: [motor_ankle, motor_ankle]\njoint_type: [FIXED, SPHERICAL]\nname_mot:"},
        ),
        "joint 'motor_ankle' is substituted twice",
    ),
    "one type for two pairs": (
        _case("cassie_like", {"type: ['6d', '6d']": "type: ['6d']"}),
        "needs one type per closed_loop pair",
    ),
    "a 4d pair": (_case("talos_like", {"type: ['6d']": "type: ['4d']"}), "'4d' is not '3d' or '6d'"),
    "a pair of three frames": (
        _case("talos_like", {"['closedloop1_B', 'closedloop1_A']": "['closedloop1_B', 'closedloop1_A', 'pelvis']"}),
        "is not a pair of frame names",
    ),
    "a motor the URDF lacks": (
        _case("wl16_like", {"'motor_6'": "'motor_7'"}),
        "name_mot: 'motor_7' is not a moving joint of robot.urdf",
    ),
    "a motor turned into a ball": (
        _case("disney_like", {"name_mot:": "joint_name: [motor_ankle]\njoint_type: [SPHERICAL]\nname_mot:"}),
        "'motor_ankle' is a JointModelSpherical joint: it needs one freedom",
    ),
    "a motor locked by FIXED": (
        _case("disney_like", {"name_mot:": "joint_name: [motor_ankle]\njoint_type: [FIXED]\nname_mot:"}),
        "'motor_ankle' is not a moving joint of robot.urdf once substituted",
    ),
    "a pair declared twice": (
        _case(
            "talos_like",
            {
                "[['closedloop1_B', 'closedloop1_A']]": (
                    "[['closedloop1_B', 'closedloop1_A'], ['closedloop1_B', 'closedloop1_A']]"
                ),
                "type: ['6d']": "type: ['6d', '6d']",
            },
        ),
        "the pair is declared twice",
    ),
    "a pair on one body": (
        _case("5bar_linkage", {"[['closedloop1_A', 'closedloop1_B']]": "[['closedloop1_A', 'sphere']]"}),
        "both frames are on one body",
    ),
    "a U-joint's own frame as a loop frame": (
        _case(
            "battobot_6d",
            {'["closedloop_knee_left_A", "closedloop_knee_left_B"]': '["free_knee_left", "closedloop_knee_left_B"]'},
        ),
        "frame 'free_knee_left' is not a frame of robot.urdf",
    ),
    "not YAML": (_case("robot_delta", {"closed_loop: [[": "closed_loop: [[[["}), "not YAML"),
    "a negative mass in the URDF": (
        _case("robot_delta", urdf={'<mass value="0.0197': '<mass value="-0.0197'}),
        "is negative",
    ),
    "an inertia that is not positive semi-definite": (
        _case("5bar_linkage", urdf={'ixx="0.68085505004432478326"': 'ixx="-0.68085505004432478326"'}),
        "not positive semi-definite",
    ),
}


@pytest.mark.parametrize("case", list(MALFORMED))
def test_a_malformed_extended_urdf_is_one_named_line_from_the_cli(case, tmp_path, capsys):
    texts, needle = MALFORMED[case]
    for name, text in texts.items():
        (tmp_path / name).write_text(text)
    assert main(["report", str(tmp_path / "robot.urdf")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and needle in err[0] and "Traceback" not in err[0], err


def test_in_a_real_process_the_field_file_mechkit_refuses_is_one_line_and_exit_status_2():
    out = subprocess.run(
        [sys.executable, "-m", "mechkit", "report", str(_urdf("disney_robot"))],
        capture_output=True,
        text=True,
        check=False,
    )
    assert out.returncode == 2 and out.stdout == ""
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and "left_spherical_free_foot" in lines[0] and "Traceback" not in out.stderr
