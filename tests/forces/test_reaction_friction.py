"""`mechkit.forces.reaction_friction`: a pin's friction torque from the reaction it carries (Adams' load
measure), on tree joints and loop cuts alike."""

from __future__ import annotations

import numpy as np
import pytest

import mechkit
from mechkit import forces
from mechkit.base.exceptions import InvalidParameters

from .states import state


def test_reaction_friction_load_measure():
    """T = mu [r (F_pre + F_r + M_b / b) + r_c F_a], every share by hand."""
    spec = forces.PinFriction(0.1, 0.01, bending_arm=0.05, collar_radius=0.02, preload=3.0)
    axis = np.array([0.0, 1.0, 0.0])
    wrench = np.array([3.0, -2.0, 4.0, 0.6, 9.0, -0.8])  # F_r = 5, F_a = 2, M_b = 1 (the axial moment 9 is not a load)
    assert spec.torque(wrench, axis) == pytest.approx(0.1 * (0.01 * (3.0 + 5.0 + 1.0 / 0.05) + 0.02 * 2.0))
    with pytest.raises(InvalidParameters, match="radius"):
        forces.ReactionFriction(mechkit.load("four_bar").model, ("crank",), (), {"crank": forces.PinFriction(0.1, 0.0)})


def test_torques_oppose_the_relative_rates_on_tree_and_cut_joints(four_bar):
    """With given reactions at every joint (the loop cut C included): no load before the reactions are known;
    then each tree joint's generalised force is -T tanh(rate / threshold), the cut's torque acts on both
    its bodies as equal and opposite moments about its axis, and the power is sum torque * relative rate
    (checked against the generalised forces of the loads: J^T fext . v + tau . v), never positive."""
    m = four_bar
    cm = m.closure_model
    spec = forces.PinFriction(0.2, 0.01, threshold=0.5)
    f = forces.ReactionFriction(m.model, cm.joint_names, cm.kernel.cuts, {j: spec for j in cm.joint_names})
    s = state(m)
    assert f.load(s).power == 0.0 and not np.any(f.load(s).generalized)
    rng = np.random.default_rng(3)
    s.reactions = rng.normal(size=(len(cm.joint_names), 6)) * 10.0
    load = f.load(s)
    sizes = f.torques(s)
    assert set(sizes) == set(cm.joint_names) and min(sizes.values()) > 0
    for joint in cm.joint_names[: m.model.njoints - 1]:
        rate = s.v[m.v_index(joint)]
        assert load.generalized[m.v_index(joint)] == pytest.approx(-sizes[joint] * np.tanh(rate / 0.5), rel=1e-12)
    total = forces.generalized_of_wrenches(m.model, s.data, load.wrenches)
    moments = load.wrenches[:, 3:]
    world = [s.data.oMi[j].rotation @ moments[j] for j in range(m.model.njoints)]
    assert np.allclose(sum(world), 0.0, atol=1e-12)  # the cut's torques: action and reaction
    assert load.power == pytest.approx(float((load.generalized + total) @ s.v), rel=1e-10)
    assert load.power < 0


def test_a_joint_that_is_not_revolute_is_refused():
    """Friction from the reaction on the slider-crank's prismatic slider: refused, naming the joint."""
    import tests_support

    m = mechkit.load(tests_support.FIXTURES / "slider_crank.urdf")
    cm = m.closure_model
    prismatic = [
        j
        for j in cm.joint_names[: m.model.njoints - 1]
        if m.model.joints[m.joint_id(j)].shortname().startswith("JointModelP")
    ]
    assert prismatic
    with pytest.raises(InvalidParameters, match="revolute joints only"):
        forces.ReactionFriction(m.model, cm.joint_names, cm.kernel.cuts, {prismatic[0]: forces.PinFriction(0.1, 0.01)})


@pytest.mark.parametrize(
    "args, named",
    [
        ((-0.1, 0.01), "friction mu"),
        ((float("nan"), 0.01), "friction mu"),
        ((0.1, 0.0), "friction radius"),
        ((0.1, -1.0), "friction radius"),
        ((0.1, 0.01, 0.0), "friction bending_arm"),
        ((0.1, 0.01, float("inf"), -1.0), "friction collar_radius"),
    ],
)
def test_friction_no_pin_can_have_is_refused_by_name(args, named):
    """A negative coefficient was accepted and only checked, if at all, when the element was built."""
    with pytest.raises(InvalidParameters, match=named):
        forces.PinFriction(*args)
