"""Only the part a study needs (`mechkit.reduction`): locked joints, a kept subsystem, a fixed root give
the same dynamics as the whole mechanism for the part that moves."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from sources.field_cli import report

import mechkit
from mechkit.base.exceptions import InvalidArgument, MalformedDescription

CASSIE = Path(__file__).resolve().parent / "fixtures" / "field" / "menagerie" / "agility_cassie" / "cassie.xml"


def test_a_locked_crank_leaves_a_four_bar_with_the_same_effort(load_cached):
    """The five-bar with prox2 locked at its home value: a one-freedom linkage whose prox1 effort is the
    whole five-bar's prox1 effort when prox2 is held still."""
    whole = load_cached("five_bar")
    locked = mechkit.load("five_bar", lock={"prox2": float(whole.home_q[whole.q_index("prox2")])})
    assert locked.mobility().dof == 1 and locked.actuated == ("prox1",)
    v = whole.velocities(whole.home_q, [0.7, 0.0])
    a = whole.accelerations(whole.home_q, v, [-0.4, 0.0])
    effort = whole.inverse_dynamics(whole.home_q, v, a).efforts["prox1"]
    q = locked.home_q
    vr = locked.velocities(q, [0.7])
    ar = locked.accelerations(q, vr, [-0.4])
    assert locked.inverse_dynamics(q, vr, ar).efforts["prox1"] == pytest.approx(effort, rel=1e-10)


def test_one_cassie_leg_kept_moves_as_in_the_whole_robot():
    """Cassie with the pelvis fixed at its keyframe "home": the left leg kept alone (the right leg and the
    pelvis welded) has the whole robot's left-leg accelerations under the same motor torques, and its
    inverse dynamics gives those torques back (statics fixes every one there)."""
    whole = mechkit.load(CASSIE, fix=["cassie-pelvis"])
    left = [b for b in (f.name for f in whole.model.frames if f.type.name == "BODY") if b.startswith("left-")]
    leg = mechkit.load(CASSIE, fix=["cassie-pelvis"], keep=left)
    assert leg.mobility().dof == 8 and whole.mobility().dof == 16
    assert set(leg.actuated) == {a for a in whole.actuated if a.startswith("left-")}
    rng = np.random.default_rng(0)
    torques = {a: float(rng.normal(0.0, 5.0)) for a in whole.actuated}
    q, v = whole.home_q, np.zeros(whole.model.nv)
    a_whole = whole.forward_dynamics(q, v, whole.generalized_forces(torques), "kkt").a
    leg_torques = {a: torques[a] for a in leg.actuated}
    a_leg = leg.forward_dynamics(leg.home_q, np.zeros(leg.model.nv), leg.generalized_forces(leg_torques), "kkt").a
    for joint in leg.model.names[1:]:
        assert a_leg[leg.v_index(joint)] == pytest.approx(
            a_whole[whole.v_index(joint)], abs=1e-9 * np.abs(a_whole).max()
        )
    back = leg.inverse_dynamics(leg.home_q, np.zeros(leg.model.nv), a_leg)
    whole_back = whole.inverse_dynamics(q, v, a_whole)
    for motor, torque in leg_torques.items():
        assert back.efforts_determinate[motor] and whole_back.efforts_determinate[motor]
        assert back.efforts[motor] == pytest.approx(torque, rel=1e-8, abs=1e-9)


def test_one_cassie_leg_holds_with_the_whole_robots_efforts():
    """`mechkit report` on Cassie with its pelvis fixed (--fix), on its left leg kept alone (--keep) and with
    its right leg locked where the whole robot's home puts it (--lock, a ball joint by its rotation
    vector): the left leg's springs and achilles rod settle the same way, and its motors hold it with
    the same efforts, to 1e-8."""
    whole = mechkit.load(CASSIE, fix=["cassie-pelvis"])
    left = [f.name for f in whole.model.frames if f.type.name == "BODY" and f.name.startswith("left-")]
    right = {j: np.atleast_1d(v) for j, v in whole.joint_values(whole.home_q).items() if j.startswith("right-")}
    runs = {
        "fix": report(CASSIE, "--fix", "cassie-pelvis"),
        "keep": report(CASSIE, "--fix", "cassie-pelvis", "--keep", ",".join(left)),
        "lock": report(
            CASSIE,
            "--fix",
            "cassie-pelvis",
            *(f"--lock={j}={','.join(repr(float(x)) for x in v)}" for j, v in right.items()),
        ),
    }
    motors = [a for a in whole.actuated if a.startswith("left-")]
    assert runs["keep"]["actuated"] == runs["lock"]["actuated"] == motors
    assert runs["keep"]["dof"] == runs["lock"]["dof"] == runs["fix"]["dof"] // 2 == 8
    efforts = {name: r["holding"]["efforts"] for name, r in runs.items()}
    for name in ("keep", "lock"):
        assert runs[name]["holding"]["undetermined"] == []
        assert sorted(runs[name]["holding"]["settled"]) == sorted(
            j for j in runs["fix"]["holding"]["settled"] if j.startswith("left-")
        )
        for motor in motors:
            assert efforts[name][motor] == pytest.approx(
                efforts["fix"][motor], abs=1e-8 * max(1.0, abs(efforts["fix"][motor]))
            )


def test_refusals_name_what_is_wrong(load_cached):
    with pytest.raises(InvalidArgument, match="keep"):
        mechkit.load("four_bar", keep=["nowhere"])
    with pytest.raises(InvalidArgument, match="lock"):
        mechkit.load("four_bar", lock={"nope": 0.0})
    with pytest.raises(MalformedDescription, match="leave it open"):
        mechkit.load("four_bar", lock={"crank": 0.6, "rocker": 0.0, "coupler": 0.0})
