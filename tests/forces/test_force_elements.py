"""Force elements (`mechkit.forces`): each element's load against an independent computation of the same
physics, its energy role, and what a file declares."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit import core, forces
from mechkit.base.exceptions import InvalidParameters


@pytest.fixture(scope="module")
def four_bar(load_cached):
    return load_cached("four_bar")


def state(m, q=None, v=None, t=0.0):
    q = m.assemble([0.9]) if q is None else q
    v = m.velocities(q, [1.5]) if v is None else v
    return forces.ForceState.at(m.model, m.model.createData(), q, v, t)


def test_joint_springs_keep_their_behaviour_and_split_their_power(four_bar):
    """The springs' forces are unchanged; as an element, its power is the dampers' alone and its energy the
    springs' potential, whose derivative along v is minus the springs' power."""
    m = four_bar
    springs = forces.JointSprings(m.model, [core.JointSpring("crank", 2.0, 0.3, 0.5, 0.1)])
    s = state(m)
    load = springs.load(s)
    x, rate = s.q[m.q_index("crank")], s.v[m.v_index("crank")]
    assert load.generalized[m.v_index("crank")] == pytest.approx(0.5 - 2.0 * (x - 0.3) - 0.1 * rate)
    assert load.power == pytest.approx(-0.1 * rate**2)
    h = 1e-6
    dV = (springs.energy(m.model, None, pin.integrate(m.model, s.q, h * s.v))
          - springs.energy(m.model, None, pin.integrate(m.model, s.q, -h * s.v))) / (2 * h)
    spring_power = (0.5 - 2.0 * (x - 0.3)) * rate
    assert dV == pytest.approx(-spring_power, rel=1e-8)


def test_coulomb_friction_is_regularised_and_dissipates(four_bar):
    m = four_bar
    f = forces.CoulombFriction(m.model, {"crank": 0.2, "rocker": 0.1})
    s = state(m)
    load = f.load(s)
    for joint, size in (("crank", 0.2), ("rocker", 0.1)):
        rate = s.v[m.v_index(joint)]
        assert load.generalized[m.v_index(joint)] == pytest.approx(-size * math.tanh(rate / forces.SPEED_THRESHOLD))
    assert load.power < 0
    assert f.load(state(m, v=np.zeros(3))).power == 0.0
    with pytest.raises(InvalidParameters, match="threshold"):
        forces.CoulombFriction(m.model, {"crank": 0.2}, threshold=0.0)


def test_gravity_element_replaces_the_models(four_bar):
    """Gravity(g) plus the model's gravity act as g alone: the generalised forces equal Pinocchio's gravity
    torques computed with a model whose gravity is g."""
    m = four_bar
    g = np.array([1.0, 0.0, -3.0])
    element = forces.Gravity(m.model, g)
    s = state(m)
    tau = forces.generalized_of_wrenches(m.model, s.data, element.load(s).wrenches)
    other = m.model.copy()
    other.gravity.linear = g
    expected = -pin.computeGeneralizedGravity(other, other.createData(), s.q) + pin.computeGeneralizedGravity(
        m.model, m.model.createData(), s.q)
    assert np.allclose(tau, expected, atol=1e-12)
    total = pin.computePotentialEnergy(m.model, m.model.createData(), s.q) + element.energy(m.model, s.data, s.q)
    assert total == pytest.approx(pin.computePotentialEnergy(other, other.createData(), s.q), abs=1e-12)


def test_body_wrench_power_and_generalised_force(four_bar):
    """A force through a body point: its generalised force is J_p^T f (Pinocchio's frame Jacobian of that
    point) and its power f . v_p."""
    m = four_bar
    point = np.array([0.03, 0.0, 0.01])
    w = forces.BodyWrench(m.model, "coupler", force=(0.5, 0.0, -2.0), point=point)
    s = state(m)
    load = w.load(s)
    tau = forces.generalized_of_wrenches(m.model, s.data, load.wrenches)
    jid = m.model.getJointId("coupler")
    model = m.model.copy()
    fid = model.addFrame(pin.Frame("p", jid, 0, pin.SE3(np.eye(3), point), pin.FrameType.OP_FRAME))
    data = model.createData()
    pin.computeJointJacobians(model, data, s.q)
    pin.updateFramePlacements(model, data)
    Jp = pin.getFrameJacobian(model, data, fid, pin.LOCAL_WORLD_ALIGNED)[:3]
    assert np.allclose(tau, Jp.T @ np.array([0.5, 0.0, -2.0]), atol=1e-12)
    assert load.power == pytest.approx(float(np.array([0.5, 0.0, -2.0]) @ (Jp @ s.v)), rel=1e-12)


def test_torque_motor_envelope():
    assert forces.envelope(5.0, 0.0, 2.0, 10.0) == 2.0  # stall
    assert forces.envelope(5.0, 5.0, 2.0, 10.0) == pytest.approx(1.0)  # half the no-load rate: half the stall
    assert forces.envelope(-5.0, 5.0, 2.0, 10.0) == pytest.approx(-3.0)  # braking against the motion
    assert forces.envelope(0.5, 5.0, math.inf, 10.0) == 0.5


def test_reaction_friction_load_measure():
    """T = mu [r (F_pre + F_r + M_b / b) + r_c F_a], every share by hand."""
    spec = forces.PinFriction(0.1, 0.01, bending_arm=0.05, collar_radius=0.02, preload=3.0)
    axis = np.array([0.0, 1.0, 0.0])
    wrench = np.array([3.0, -2.0, 4.0, 0.6, 9.0, -0.8])  # F_r = 5, F_a = 2, M_b = 1 (the axial moment 9 is not a load)
    assert spec.torque(wrench, axis) == pytest.approx(0.1 * (0.01 * (3.0 + 5.0 + 1.0 / 0.05) + 0.02 * 2.0))
    with pytest.raises(InvalidParameters, match="radius"):
        forces.ReactionFriction(mechkit.load("four_bar").model, ("crank",), (), {"crank": forces.PinFriction(0.1, 0.0)})


def test_a_file_declares_dampers_friction_and_limits(four_bar):
    urdf = four_bar.urdf.replace('<limit effort="1e6" lower="-25.0" upper="25.0" velocity="1e3"/>',
                                 '<limit effort="7" lower="-2" upper="2.5" velocity="3"/>'
                                 '<dynamics damping="0.05" friction="0.02"/>', 1)
    d = forces.described.from_urdf(urdf, four_bar.model, ("crank",))
    first = next(iter(d.limits))
    assert d.limits[first] == (-2.0, 2.5) and d.dampers == {first: 0.05} and d.friction == {first: 0.02}
    assert d.motors == {"crank": (7.0, 3.0)} if first == "crank" else d.motors == {"crank": (1e6, 1e3)}
    names = [e.name for e in d.elements(four_bar.model)]
    assert names == ["joint dampers", "joint friction"]


def test_mjcf_frictionloss_and_ranges(tmp_path):
    pytest.importorskip("mujoco")
    from mechkit.export.mjcf import to_mjcf

    m = mechkit.load("four_bar")
    text = to_mjcf(m).replace('ref="0.6" range="-25.0 25.0"', 'ref="0.6" range="-1 2" frictionloss="0.03"', 1)
    path = tmp_path / "fb.xml"
    path.write_text(text)
    d = forces.read_described(path, None, m.model)
    assert d.friction == {"crank": 0.03} and d.limits["crank"] == (-1.0, 2.0)
