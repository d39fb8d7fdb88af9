"""Every robot of Gepetto's example-parallel-robots through `mechkit report` (the command line, JSON) against
the independent computations of `independent` on the model Gepetto's loader builds (`gepetto_load`,
with the URDF's mimic rows), at the configuration the report holds (its home, with the joints no motor
drives settled): that configuration closes Gepetto's own cuts, and there the DOF, the idle freedoms,
whether the motors hold gravity, which efforts statics fixes and those efforts (to 1e-8) agree. On a
free-flyer root nothing holds the robot and the report says so; the robots whose published loops
cannot close, and the one whose sidecar misspells a joint, are refused in one line."""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from .field_cli import refusal, report
from .independent import Cut, gepetto_load, idle, require_closed, study, urdf_mimics

GEPETTO = Path(__file__).resolve().parents[1] / "fixtures" / "field" / "gepetto"
ROBOTS = sorted(p.name for p in GEPETTO.iterdir() if p.is_dir())
#: robot -> what its one-line refusal says.
REFUSED = {
    "kangaroo_like": "its loops do not close at home",
    "kangaroo_like_2legs": "its loops do not close at home",
    "disney_robot": "'left_spherical_free_foot' is not a joint of robot.urdf",
}
#: Gepetto's `robot_options`: these float on a free-flyer root by default.
FREE_FLYING = ("battobot_6d", "digit_like_2legs", "digit_like_2legs_6D", "disney_like", "true_talos_2_legs")
#: Robots whose unsettled home leaves load on the motions no motor drives (rods whose centre of mass is off
#: their spin axis, a leg of a Stewart platform, the 0.3 mm-off ankle rod of disney_like): the report
#: settles them, and the independent study agrees the motors hold there, not at home.
SETTLE = ("disney_like", "talos_like", "wl16_like")


def _urdf(robot: str) -> Path:
    return next((GEPETTO / robot).glob("*.urdf"))


@functools.cache
def _gepettos(robot: str, freeflyer: bool = False) -> tuple[pin.Model, list[Cut], list[str]]:
    return gepetto_load(_urdf(robot), GEPETTO / robot / "robot.yaml", freeflyer)


def _groups_of(model: pin.Model, bodies: dict[str, int], groups: dict[frozenset, int]) -> dict[frozenset, int]:
    """The report's idle freedoms (body name -> count) keyed like `independent.idle` (the joint names of
    the welded group the body's joint belongs to)."""
    out = {}
    for body, count in bodies.items():
        joint = model.names[model.frames[model.getFrameId(body, pin.FrameType.BODY)].parentJoint]
        out[next((g for g in groups if joint in g), frozenset({joint}))] = count
    return out


@pytest.mark.parametrize("robot", [r for r in ROBOTS if r not in REFUSED])
def test_the_report_agrees_with_an_independent_computation_at_the_configuration_it_holds(robot):
    r = report(_urdf(robot))
    model, cuts, motors = _gepettos(robot)
    held = r["holding"]
    assert "efforts" in held, held
    q = np.array(held["q"])
    require_closed(robot, model, cuts, q)  # Gepetto's own cuts (log6 of 6d pairs): a flipped weld would not pass
    found = study(model, cuts, motors, q, couplings=urdf_mimics(_urdf(robot)))
    assert np.max(np.abs(pin.difference(model, q, found.q))) < 1e-9  # the independent closure stays there
    assert r["dof"] == found.dof
    groups = idle(model, cuts, q, urdf_mimics(_urdf(robot)))
    assert _groups_of(model, r["idle"], groups) == groups
    assert found.holds and bool(held["settled"]) == (robot in SETTLE)
    assert sorted(held["undetermined"]) == sorted(set(motors) - set(found.determined))
    scale = max(1.0, max(abs(t) for t in found.torques.values()))
    for motor in found.determined:
        assert held["efforts"][motor] == pytest.approx(found.torques[motor], abs=1e-8 * scale), motor


@pytest.mark.parametrize("robot", SETTLE)
def test_at_the_unsettled_home_the_motors_cannot_hold(robot):
    """Where the report settled, the home itself leaves gravity unbalanced along the undriven motions."""
    r = report(_urdf(robot))
    model, cuts, motors = _gepettos(robot)
    home = study(model, cuts, motors, np.array(r["home_q"]), couplings=urdf_mimics(_urdf(robot)))
    assert not home.holds and home.gravity_residual > 1e-7


@pytest.mark.parametrize("robot", FREE_FLYING)
def test_on_a_free_flyer_root_the_report_says_nothing_holds_it(robot):
    r = report(_urdf(robot), "--freeflyer")
    model, cuts, motors = _gepettos(robot, True)
    found = study(model, cuts, motors, np.array(r["home_q"]), couplings=urdf_mimics(_urdf(robot)))
    assert r["dof"] == found.dof and not found.holds
    body = model.frames[
        next(i for i, f in enumerate(model.frames) if f.type == pin.FrameType.BODY and f.parentJoint == 1)
    ].name
    assert r["holding"] == {
        "refused": f"floating root 'root_joint': nothing holds its weight (fix its body: --fix {body})"
    }


def test_a_fixed_free_flyer_root_gives_the_fixed_base_robot():
    """cassie_like on a free-flyer, its pelvis fixed: the fixed-base robot's home and efforts."""
    fixed = report(_urdf("cassie_like"))
    floating = report(_urdf("cassie_like"), "--freeflyer", "--fix", "pelvis")
    assert sorted(floating["home"]) == sorted(fixed["home"])
    for joint, value in fixed["home"].items():
        np.testing.assert_allclose(floating["home"][joint], value, atol=1e-12)
    assert floating["holding"]["efforts"] == pytest.approx(fixed["holding"]["efforts"], abs=1e-10)


@pytest.mark.parametrize("robot", sorted(REFUSED))
def test_robots_that_cannot_load_are_refused_in_one_line_by_name(robot):
    line = refusal(_urdf(robot))
    assert REFUSED[robot] in line and robot in line
