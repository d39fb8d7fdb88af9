"""Any Pinocchio joint (`mechkit.core.joints`): values of every joint type round-trip through q, and two
mechanisms URDF cannot write (an RSSR with ball joints, a five-bar on a welded floating base) pass the
identities the built-ins pass: closure, J v = 0, J a + gamma = 0, the drift as the derivative of J v,
the forward-inverse round trip by every method, the reactions' balance and the second opinion."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from any_joint_models import floating_five_bar, rssr

from mechkit.core import joints
from mechkit.second_opinion.agreement import agreement
from mechkit.second_opinion.opinion import SecondOpinion

JOINTS = {
    "revolute": (pin.JointModelRZ(), 0.7),
    "prismatic": (pin.JointModelPX(), -0.2),
    "continuous": (pin.JointModelRUBY(), 2.9),
    "helical": (pin.JointModelHZ(0.01), 1.3),
    "ball": (pin.JointModelSpherical(), np.array([0.3, -1.1, 0.4])),
    "free-flyer": (pin.JointModelFreeFlyer(), np.array([0.1, -0.2, 0.3, 0.5, 0.2, -0.9])),
    "planar": (pin.JointModelPlanar(), np.array([0.4, -0.3, 2.5])),
    "spherical ZYX": (pin.JointModelSphericalZYX(), np.array([0.1, 0.2, 0.3])),
    "translation": (pin.JointModelTranslation(), np.array([0.1, 0.2, 0.3])),
}


@pytest.mark.parametrize("kind", JOINTS)
def test_values_round_trip_through_the_configuration(kind):
    joint, value = JOINTS[kind]
    model = pin.Model()
    j = model.addJoint(0, joint, pin.SE3.Identity(), kind)
    q = pin.neutral(model)
    joints.set_value(model, q, j, value)
    back = joints.value(model, q, j)
    assert np.max(np.abs(np.asarray(back) - value)) < 1e-14
    assert joints.size(model, j) == model.nvs[j] == np.size(value)
    # the value is the motion from the neutral configuration (the rotation vector of a ball, etc.)
    if kind in ("ball", "revolute", "prismatic", "spherical ZYX", "translation"):
        np.testing.assert_allclose(pin.difference(model, pin.neutral(model), q), value, atol=1e-14)
    with pytest.raises(Exception, match=kind):
        joints.set_value(model, q, j, np.zeros(np.size(value) + 1))


@pytest.fixture(scope="module", params=["rssr", "floating_five_bar"])
def mech(request):
    return {"rssr": rssr, "floating_five_bar": floating_five_bar}[request.param]()


def _state(m, seed=0):
    rng = np.random.default_rng(seed)
    q = m.home_q
    v = m.velocities(q, rng.normal(size=len(m.actuated)))
    a = m.accelerations(q, v, rng.normal(size=len(m.actuated)))
    return q, v, a


def test_structure_and_closure(mech):
    assert np.max(np.abs(mech.closure_residual(mech.home_q))) < 1e-12
    assert mech.mobility().dof == 2 and mech.mobility().redundant == 0
    assert mech.idle == ({"ball_a": 1} if mech.spec.name == "rssr" else {})
    assert mech.urdf is None  # URDF cannot write these trees


def test_closure_identities_and_the_drift(mech):
    q, v, a = _state(mech)
    J, gamma = mech.closure_jacobian(q), mech.closure_drift(q, v)
    assert np.max(np.abs(J @ v)) < 1e-12 * max(1.0, np.max(np.abs(v)))
    assert np.max(np.abs(J @ a + gamma)) < 1e-12 * max(1.0, np.max(np.abs(gamma)))
    h = 1e-6  # gamma = d/dt (J v) along q exp(t v): on the configuration manifold (quaternions)
    fd = (
        mech.closure_jacobian(pin.integrate(mech.model, q, h * v)) @ v
        - mech.closure_jacobian(pin.integrate(mech.model, q, -h * v)) @ v
    ) / (2 * h)
    assert np.max(np.abs(gamma - fd)) < 1e-7 * max(1.0, np.max(np.abs(fd)))


def test_forward_inverse_round_trip_by_every_method(mech):
    """Efforts from the inverse dynamics give back the input accelerations by every forward method; an
    idle spin's acceleration is its own dynamics' (no actuator drives it), the rest is the given one."""
    q, v, a = _state(mech, 3)
    inv = mech.inverse_dynamics(q, v, a)
    tau = np.zeros(mech.model.nv)
    for joint, effort in inv.efforts.items():
        tau[mech.v_index(joint)] = effort
    driven = [mech.v_index(j) for j in mech.actuated]
    for method in ("kkt", "nullspace", "proximal"):
        back = mech.forward_dynamics(q, v, tau, method).a
        assert np.max(np.abs(back[driven] - a[driven])) < 1e-9 * max(1.0, np.max(np.abs(a)))
        if not mech.idle:
            assert np.max(np.abs(back - a)) < 1e-9 * max(1.0, np.max(np.abs(a)))
    if mech.idle:  # the idle spin: forward dynamics and the inverse dynamics' own choice agree
        again = mech.inverse_dynamics(q, v, mech.forward_dynamics(q, v, tau, "kkt").a)
        assert inv.efforts == pytest.approx(again.efforts, rel=1e-9)


def test_support_reactions_balance_weight_and_inertia(mech):
    q, v, a = _state(mech, 5)
    inv = mech.inverse_dynamics(q, v, a)
    if mech.idle:  # the accelerations the inverse dynamics used: the idle spin's from its dynamics
        tau = np.zeros(mech.model.nv)
        for joint, effort in inv.efforts.items():
            tau[mech.v_index(joint)] = effort
        a = mech.forward_dynamics(q, v, tau, "kkt").a
    data = mech.model.createData()
    pin.centerOfMass(mech.model, data, q, v, a)
    supports = sum(r.wrench[:3] for r in inv.reactions.values() if r.support)
    expected = data.mass[0] * (data.acom[0] - mech.model.gravity.linear)
    assert np.max(np.abs(supports - expected)) < 1e-10 * max(1.0, np.max(np.abs(expected)))


def test_the_second_opinion_agrees(mech):
    """The automatic SOC decomposition and its virtual-work solve (no Pinocchio dynamics) give the efforts
    and determinate reactions constrained RNEA gives, at states the forward dynamics produced (so that an
    idle spin accelerates as its own dynamics says)."""
    rng = np.random.default_rng(11)
    states = []
    for _ in range(3):
        q, v, _ = _state(mech, int(rng.integers(100)))
        tau = np.zeros(mech.model.nv)
        tau[[mech.v_index(j) for j in mech.actuated]] = rng.normal(size=len(mech.actuated))
        states.append((q, v, mech.forward_dynamics(q, v, tau, "kkt").a))
    report = agreement(SecondOpinion(mech), states, timing=False)
    assert report.max_relative_difference < 1e-9, report
