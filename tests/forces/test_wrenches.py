"""`mechkit.forces.wrenches`: a world force through a body point and a world moment, functions of time."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit import forces
from mechkit.base.exceptions import InvalidParameters

from .states import state


def _point_jacobian(m, joint, point, q):
    """Pinocchio's (6, nv) LOCAL_WORLD_ALIGNED Jacobian of a frame at `point` of `joint`'s body."""
    model = m.model.copy()
    fid = model.addFrame(pin.Frame("p", model.getJointId(joint), 0, pin.SE3(np.eye(3), point), pin.FrameType.OP_FRAME))
    data = model.createData()
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    return pin.getFrameJacobian(model, data, fid, pin.LOCAL_WORLD_ALIGNED)


def test_body_wrench_power_and_generalised_force(four_bar):
    """A force through a body point: its generalised force is J_p^T f (Pinocchio's frame Jacobian of that
    point) and its power f . v_p."""
    m = four_bar
    point = np.array([0.03, 0.0, 0.01])
    w = forces.BodyWrench(m.model, "coupler", force=(0.5, 0.0, -2.0), point=point)
    s = state(m)
    load = w.load(s)
    tau = forces.generalized_of_wrenches(m.model, s.data, load.wrenches)
    Jp = _point_jacobian(m, "coupler", point, s.q)[:3]
    assert np.allclose(tau, Jp.T @ np.array([0.5, 0.0, -2.0]), atol=1e-12)
    assert load.power == pytest.approx(float(np.array([0.5, 0.0, -2.0]) @ (Jp @ s.v)), rel=1e-12)


def test_a_moment_of_time_does_work_on_the_rotation(four_bar):
    """A world moment m(t) alone: its generalised force is J_w^T m(t) at the state's time and its power m . omega."""
    m = four_bar
    moment = lambda t: np.array([0.0, 0.7 * t, 0.0])
    w = forces.BodyWrench(m.model, "rocker", moment=moment)
    s = state(m, t=2.0)
    load = w.load(s)
    Jw = _point_jacobian(m, "rocker", np.zeros(3), s.q)[3:]
    assert np.allclose(forces.generalized_of_wrenches(m.model, s.data, load.wrenches), Jw.T @ moment(2.0), atol=1e-12)
    assert load.power == pytest.approx(float(moment(2.0) @ (Jw @ s.v)), rel=1e-12)


def test_bad_wrenches_are_refused_by_name(four_bar):
    with pytest.raises(InvalidParameters, match="nowhere"):
        forces.BodyWrench(four_bar.model, "nowhere")
    with pytest.raises(InvalidParameters, match="force"):
        forces.BodyWrench(four_bar.model, "coupler", force=(1.0, 2.0))
    with pytest.raises(InvalidParameters, match="moment"):
        forces.BodyWrench(four_bar.model, "coupler", moment=lambda t: np.array([np.inf, 0.0, 0.0]))
    with pytest.raises(InvalidParameters, match="point"):
        forces.BodyWrench(four_bar.model, "coupler", point=(0.0, np.nan, 0.0))
