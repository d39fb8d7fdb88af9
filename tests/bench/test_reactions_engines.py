"""mechkit's rigid reactions beside Drake's and MuJoCo's, in one convention."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit.bench import reactions_engines

pytest.importorskip("pydrake", reason="Drake not installed: pip install 'mechkit[peers]'")
pytest.importorskip("mujoco", reason="MuJoCo not installed: pip install 'mechkit[peers]'")

GRIPPER = Path(__file__).resolve().parents[1] / "fixtures" / "field" / "menagerie" / "robotiq_2f85" / "2f85.xml"


def _state(m, moving: bool):
    q = m.home_q
    v = m.velocities(q, [0.5] * len(m.actuated)) if moving else np.zeros(m.model.nv)
    return q, v, m.generalized_forces({j: 0.3 for j in m.actuated})


@pytest.mark.parametrize("moving", [False, True])
def test_drake_tree_reactions_equal_ours_on_the_four_bar(moving, load_cached):
    """Drake's Newton-Euler of the open tree under our cut wrench: its accelerations and tree-joint
    reactions (F_CJc_Jc rotated to world) are ours to round-off, static and moving."""
    m = load_cached("four_bar")
    q, v, tau = _state(m, moving)
    ours = reactions_engines.rigid(m, q, v, tau)
    ntree = m.model.njoints - 1
    theirs = reactions_engines.drake_tree(m, q, v, tau, ours["reactions"][ntree:])
    scale = np.max(np.abs(ours["reactions"][:ntree]))
    assert np.max(np.abs(theirs["reactions"] - ours["reactions"][:ntree])) < 1e-9 * scale
    assert np.max(np.abs(theirs["a"] - ours["a"])) < 1e-9 * np.max(np.abs(ours["a"]))


def test_engines_closed_models_approach_ours(load_cached):
    """Drake's SAP step and MuJoCo's soft closure: reactions near ours (SAP closer), closure errors finite
    and in that order."""
    m = load_cached("four_bar")
    out = reactions_engines.compare(m, *_state(m, True))
    scale = np.max(np.abs(out["rigid"]["reactions"]))
    sap, mj = (np.max(np.abs(out[k]["diff"])) / scale for k in ("drake_sap", "mujoco"))
    assert sap < 1e-2 and sap < mj < 0.2
    assert out["drake_tree"]["closure"] < 1e-9 < out["drake_sap"]["closure"] < out["mujoco"]["closure"]
    res = out["rigid"]["resultant"]
    off = [
        np.max(np.abs(out[k]["resultant"] - res)) / np.max(np.abs(res)) for k in ("drake_tree", "drake_sap", "mujoco")
    ]
    assert off[0] < 1e-12 < off[1] < off[2] < 0.1


def test_drake_tree_carries_our_armature():
    """The Robotiq 2F-85 (MJCF armature on its joints): Drake's open tree, armature as rotor inertia, gives
    Pinocchio's ABA accelerations."""
    m = mechkit.load(GRIPPER)
    zero = np.zeros(m.model.nv)
    ours = pin.aba(m.model, m.model.createData(), m.home_q, zero, zero)
    theirs = reactions_engines.drake_tree(m, m.home_q, zero, zero, np.zeros((len(m.cuts), 6)))["a"]
    assert np.max(np.abs(theirs - ours)) < 1e-9 * np.max(np.abs(ours))


def test_drake_tree_reactions_equal_ours_on_the_gripper():
    """The Robotiq 2F-85 (armature, joint springs, two planar connect cuts): Drake's open tree under our cut
    wrenches and the springs' torques, at rest, gives our accelerations and tree-joint reactions to round-off."""
    m = mechkit.load(GRIPPER)
    tau = m.generalized_forces({"fingers_actuator": 0.3})  # at rest: its actuator is no joint to give a rate to
    out = reactions_engines.compare(m, m.home_q, np.zeros(m.model.nv), tau)
    scale = np.max(np.abs(out["rigid"]["reactions"]))
    assert np.max(np.abs(out["drake_tree"]["diff"])) < 1e-9 * scale
    assert out["drake_tree"]["closure"] < 1e-9 * np.max(np.abs(out["rigid"]["a"]))
