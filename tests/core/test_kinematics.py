"""Closure rows and kinematics, checked for every registered mechanism (every row kind they use)."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit import core
from mechkit.base.exceptions import ClosureNotConverged
from mechkit.catalog.registry import specs

NAMES = list(specs())


def _residual(m, q):
    return m.closure_residual(q)


def _perturbed(m, scale=0.05, seed=3):
    rng = np.random.default_rng(seed)
    return pin.integrate(m.model, m.home_q, scale * rng.normal(size=m.model.nv))


@pytest.mark.parametrize("name", NAMES)
def test_closure_jacobian_is_the_derivative_of_the_residual(name, load_cached):
    m = load_cached(name)
    h = 1e-6
    rng = np.random.default_rng(11)
    for q in (m.home_q, _perturbed(m)):
        J = m.closure_jacobian(q)
        for _ in range(3):
            dq = rng.normal(size=m.model.nv)
            fd = (
                _residual(m, pin.integrate(m.model, q, h * dq)) - _residual(m, pin.integrate(m.model, q, -h * dq))
            ) / (2 * h)
            assert np.max(np.abs(J @ dq - fd)) < 1e-7 * max(1.0, np.max(np.abs(fd)))


@pytest.mark.parametrize("name", NAMES)
def test_drift_is_the_derivative_of_jv(name, load_cached):
    """gamma = d/dt (J v) along q(t) = q (+) t v, i.e. the closure acceleration at a = 0."""
    m = load_cached(name)
    h = 1e-6
    rng = np.random.default_rng(5)
    for q in (m.home_q, _perturbed(m)):
        v = rng.normal(size=m.model.nv)
        fd = (
            m.closure_jacobian(pin.integrate(m.model, q, h * v)) @ v
            - m.closure_jacobian(pin.integrate(m.model, q, -h * v)) @ v
        ) / (2 * h)
        gamma = m.closure_drift(q, v)
        assert np.max(np.abs(gamma - fd)) < 1e-6 * max(1.0, np.max(np.abs(fd)))


@pytest.mark.parametrize("name", NAMES)
def test_home_assembly_closes_and_mobility_matches_gruebler(name, load_cached):
    m = load_cached(name)
    assert np.max(np.abs(m.closure_residual(m.home_q)), initial=0.0) < 1e-12
    mob = m.mobility()
    assert mob.dof == m.spec.gruebler_dof or mob.redundant > 0, (mob, m.spec.gruebler_dof)


@pytest.mark.parametrize("name", NAMES)
def test_velocities_and_accelerations_satisfy_the_closure(name, load_cached):
    m = load_cached(name)
    if m.mobility().dof != len(m.actuated):
        pytest.skip("inputs do not determine the motion (under-actuated): see the mechanism's own tests")
    q = m.home_q
    n = len(m.actuated)
    v = m.velocities(q, np.linspace(0.5, 1.0, n))
    a = m.accelerations(q, v, np.linspace(-0.3, 0.2, n))
    assert np.max(np.abs(m.closure_jacobian(q) @ v)) < 1e-10 * max(1.0, np.max(np.abs(v)))
    assert np.max(np.abs(m.closure_jacobian(q) @ a + m.closure_drift(q, v))) < 1e-9 * max(1.0, np.max(np.abs(a)))


@pytest.mark.parametrize("method", ["newton", "lm"])
def test_assembly_follows_the_guess_to_either_branch(method, load_cached):
    m = load_cached("four_bar")
    up = m.assemble([1.0], method=method)
    p = m.params
    # the crossed branch: mirror C about the line B-D
    down = m.assemble([1.0], guess={"coupler": -1.9, "rocker": -1.5}, method=method)
    z = []
    for q in (up, down):
        data = m.model.createData()
        pin.framesForwardKinematics(m.model, data, q)
        z.append(data.oMf[m.model.getFrameId("rocker_C")].translation[2])
        assert np.max(np.abs(m.closure_residual(q))) < 1e-12
    assert z[0] > 0 > z[1], z
    assert p.crank > 0


def test_velocity_matches_finite_difference_of_assembly(load_cached):
    m = load_cached("five_bar")
    q0 = m.home_q
    h = 1e-6
    rates = np.array([0.7, -0.4])
    th = np.array([2.0, 1.1])
    qp = m.assemble(th + h * rates, guess=q0)
    qm = m.assemble(th - h * rates, guess=q0)
    v = m.velocities(q0, rates)
    assert np.max(np.abs((qp - qm) / (2 * h) - v)) < 1e-7


def test_unreachable_input_raises_with_residual(load_cached):
    m = load_cached("five_bar")
    with pytest.raises(ClosureNotConverged) as err:
        m.assemble([np.pi, 0.0])  # |B1 B2| = 0.49 > 0.44: the distal links cannot meet
    assert err.value.residual > 1e-3


def test_a_model_of_one_velocity_gets_its_jacobian_as_a_column():
    """Pinocchio gives `data.J` as a (6,) vector when nv = 1: a body on a revolute joint, closed to the
    ground by a planar cut about the same axis through a point off it, has a (rows, 1) closure Jacobian
    equal to the residual's central difference, and its loop closes where the two pins coincide (q = 0)."""
    model = pin.Model()
    j = model.addJoint(0, pin.JointModelRZ(), pin.SE3.Identity(), "hinge")
    model.appendBodyToJoint(j, pin.Inertia.FromBox(1.0, 0.1, 0.1, 0.1), pin.SE3.Identity())
    point = pin.SE3(np.eye(3), np.array([0.2, 0.0, 0.0]))
    model.addFrame(pin.Frame("on_ground", 0, point, pin.FrameType.OP_FRAME))
    model.addFrame(pin.Frame("on_body", j, point, pin.FrameType.OP_FRAME))
    cm = core.ClosureModel(model, [core.LoopClosure("pin", "revolute", "on_ground", "on_body", axis=(0.0, 0.0, 1.0))])
    cd = cm.create_data()
    q, h = np.array([0.3]), 1e-6
    jac = core.closure_jacobian(cm, cd, q)
    numeric = (core.closure_residual(cm, cd, q + h) - core.closure_residual(cm, cd, q - h)) / (2 * h)
    assert jac.shape == (numeric.size, 1) and np.abs(jac[:, 0] - numeric).max() < 1e-9
    closed = core.assemble(cm, cd, q, cm.split(()))
    assert closed.residual < 1e-12 and abs(closed.q[0]) < 1e-9
