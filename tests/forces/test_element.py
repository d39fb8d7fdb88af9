"""`mechkit.forces.element`: the state elements are evaluated at, and body wrenches in Pinocchio's `fext`
convention turned into generalised forces, against Pinocchio's own inverse dynamics with `fext`."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit import forces

from .states import state


def test_generalised_forces_of_wrenches_match_pinocchios_fext(four_bar):
    """J^T f of random body wrenches equals what Pinocchio's RNEA removes from the joint torques when the
    same wrenches are given as `fext`: rnea(q, v, a) - rnea(q, v, a, fext)."""
    m = four_bar
    s = state(m)
    rng = np.random.default_rng(7)
    wrenches = rng.normal(size=(m.model.njoints, 6))
    wrenches[0] = 0.0
    fext = pin.StdVec_Force()
    for row in wrenches:
        fext.append(pin.Force(row[:3].copy(), row[3:].copy()))
    a = rng.normal(size=m.model.nv)
    data = m.model.createData()
    expected = pin.rnea(m.model, data, s.q, s.v, a).copy() - pin.rnea(m.model, data, s.q, s.v, a, fext)
    assert np.allclose(forces.generalized_of_wrenches(m.model, s.data, wrenches), expected, atol=1e-12)


def test_a_world_force_at_a_world_point_becomes_its_fext_row(four_bar):
    """`wrench_on_body`: the row, carried back to the world by the joint's placement, is the force and its
    moment about the world origin, m + p x f (a force through p and a moment m)."""
    m = four_bar
    s = state(m)
    joint = m.model.getJointId("coupler")
    force, moment, point = np.array([1.0, -2.0, 0.5]), np.array([0.1, 0.3, -0.2]), np.array([0.2, 0.05, -0.1])
    row = forces.wrench_on_body(m.model, s.data, joint, force, moment, point)
    world = s.data.oMi[joint].act(pin.Force(row))
    assert np.allclose(world.linear, force, atol=1e-14)
    assert np.allclose(world.angular, moment + np.cross(point, force), atol=1e-14)


def test_the_state_carries_the_kinematics_of_q_and_v(four_bar):
    """`ForceState.at` leaves the data with q's placements and v's velocities (Pinocchio's own pass
    repeated), no reactions, and the time given."""
    m = four_bar
    s = state(m, t=1.25)
    data = m.model.createData()
    pin.forwardKinematics(m.model, data, s.q, s.v)
    for j in range(1, m.model.njoints):
        assert np.allclose(s.data.oMi[j].homogeneous, data.oMi[j].homogeneous, atol=1e-15)
        assert np.allclose(s.data.v[j].vector, data.v[j].vector, atol=1e-15)
    assert s.reactions is None and s.t == 1.25
    with pytest.raises(NotImplementedError):
        forces.ForceElement().load(s)
    assert forces.ForceElement().energy(m.model, s.data, s.q) == 0.0
