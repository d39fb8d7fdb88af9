"""MuJoCo Menagerie's Cassie (floating, and with its pelvis fixed) and Robotiq 2F-85 through `mechkit report`
(the command line, JSON), against MuJoCo's own functions on the same files (`mujoco_reference`) at the
configuration the report holds: the closure from MuJoCo's equality rows, the DOF from their rank, and
the holding efforts with springs (to 1e-8). Cassie's home is its keyframe "home" (the reader takes it),
its springs and achilles rods settled there by the report; the floating robot and the gripper, whose
fingers rest on their stops, are refused by name."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import mechkit

pytest.importorskip("mujoco")

from mechkit.sources.mjcf import read_mjcf

from .field_cli import report
from .mujoco_reference import MujocoReference

MENAGERIE = Path(__file__).resolve().parents[1] / "fixtures" / "field" / "menagerie"
CASSIE = MENAGERIE / "agility_cassie" / "cassie.xml"
GRIPPER = MENAGERIE / "robotiq_2f85" / "2f85.xml"
TOL = 1e-8


def _dof(ref: MujocoReference, q: np.ndarray) -> int:
    """nv - the rank of MuJoCo's equality rows at q, closed by them to 1e-10."""
    mj = ref.at(q)
    assert np.max(np.abs(mj["residual"]), initial=0.0) < 1e-10
    return ref.model.nv - np.linalg.matrix_rank(mj["J"], 1e-9 * np.max(np.abs(mj["J"])))


def _on(model: pin.Model, q: np.ndarray, other: pin.Model) -> np.ndarray:
    """A configuration of `model` as one of `other` (joints matched by name, the others neutral)."""
    out = pin.neutral(other)
    for j in range(1, model.njoints):
        if other.existJointName(model.names[j]):
            a, b = model.joints[j], other.joints[other.getJointId(model.names[j])]
            out[b.idx_q : b.idx_q + b.nq] = q[a.idx_q : a.idx_q + a.nq]
    return out


def test_floating_cassie_reports_its_dof_and_idle_rods_and_that_nothing_holds_its_pelvis():
    r = report(CASSIE)
    ref = MujocoReference(CASSIE, read_mjcf(CASSIE).model)
    assert r["dof"] == _dof(ref, np.array(r["home_q"])) == 22
    assert r["idle"] == {"left-achilles-rod": 1, "right-achilles-rod": 1}
    assert r["holding"] == {
        "refused": "floating root 'joint0': nothing holds its weight (fix its body: --fix cassie-pelvis)"
    }


def test_cassie_with_its_pelvis_fixed_holds_with_mujocos_efforts_where_its_springs_settle(tmp_path):
    """--fix cassie-pelvis: the motors at the keyframe "home", the shins, heel springs and achilles rods
    settled; MuJoCo's efforts on the file with its pelvis welded (no free joint) there, ours to 1e-8."""
    r = report(CASSIE, "--fix", "cassie-pelvis")
    fixed = tmp_path / "cassie_fixed.xml"
    fixed.write_text(
        re.sub(r"<keyframe>.*</keyframe>", "", CASSIE.read_text().replace("<freejoint/>", ""), flags=re.DOTALL)
    )
    theirs = read_mjcf(fixed).model
    ours = mechkit.load(CASSIE, fix=["cassie-pelvis"]).model
    ref = MujocoReference(fixed, theirs)
    held = r["holding"]
    q = _on(ours, np.array(held["q"]), theirs)
    assert r["dof"] == _dof(ref, q) == 16
    assert sorted(held["settled"]) == sorted(
        f"{s}-{j}" for s in ("left", "right") for j in ("achilles-rod", "shin", "tarsus", "heel-spring")
    )
    u_mj, left = ref.efforts(q)
    assert left < TOL  # MuJoCo agrees that the motors hold there
    u = np.array([held["efforts"][a] for a in r["actuated"]])
    np.testing.assert_allclose(u, ref.in_our_units(u_mj), rtol=0, atol=TOL * max(1.0, np.max(np.abs(u))))
    home = MujocoReference(CASSIE, read_mjcf(CASSIE).model)  # the keyframe's motor angles are the held ones
    key = home.joint_values(home.mm.key_qpos[0])
    for motor in r["actuated"]:
        assert held["q"][ours.joints[ours.getJointId(motor)].idx_q] == pytest.approx(key[motor], abs=1e-12)


def test_the_2f85_reports_its_dof_and_that_its_fingers_rest_on_their_stops():
    r = report(GRIPPER)
    ref = MujocoReference(GRIPPER, read_mjcf(GRIPPER).model)
    assert r["dof"] == _dof(ref, np.array(r["home_q"])) == 3 and r["idle"] == {}
    assert r["holding"]["refused"].startswith(
        "the joints no actuator drives settle against a stop: right_coupler_joint"
    )
    assert "outside its range [-1.57, 0]" in r["holding"]["refused"]
