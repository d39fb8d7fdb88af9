"""A base's prescribed motion: derivatives from the law (checked) or a spline, the CSV file, and the
carried input law, whose root joints put the carrier where the law says (Pinocchio's kinematics)."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit.base.exceptions import InvalidArgument, MalformedDescription
from mechkit.bases import CARRIER_FRAME, base_motion, with_base

W = 2 * np.pi / 3.0  # a 3 s roll and pitch period (ours)
AMP = np.array([0.02, -0.01, 0.03, 0.12, 0.08, 0.05])  # m, rad


def _pose(t):
    return AMP * np.sin(W * t + np.arange(6))


def _law(t):
    phase = W * t + np.arange(6)
    return AMP * np.sin(phase), AMP * W * np.cos(phase), -AMP * W**2 * np.sin(phase)


def test_law_rates_checked_and_differences_agree():
    t = np.linspace(0, 3, 31)
    given = base_motion.from_callable(_law, t)
    differenced = base_motion.from_callable(_pose, t)
    np.testing.assert_allclose(differenced.rates, given.rates, atol=1e-9)
    np.testing.assert_allclose(differenced.accelerations, given.accelerations, atol=1e-6)
    with pytest.raises(InvalidArgument, match="law rates"):
        base_motion.from_callable(lambda x: (_law(x)[0], 2 * _law(x)[1], _law(x)[2]), t)
    with pytest.raises(InvalidArgument, match="law"):
        base_motion.from_callable(lambda x: np.zeros(5), t)


def test_csv_spline_derivatives(tmp_path):
    """A CSV of 301 samples of the law: the spline's rates within 1e-5 of the law's inside the span."""
    t = np.linspace(0, 3, 301)
    path = tmp_path / "carrier.csv"
    rows = ["t," + ",".join(base_motion.POSE_COLUMNS)] + [",".join(f"{v:.17g}" for v in [x, *_pose(x)]) for x in t]
    path.write_text("\n".join(rows) + "\n")
    motion = base_motion.from_csv(path)
    exact = base_motion.from_callable(_law, t)
    inside = slice(10, -10)
    assert np.abs(motion.rates[inside] - exact.rates[inside]).max() < 1e-5
    assert np.abs(motion.accelerations[inside] - exact.accelerations[inside]).max() < 1e-3
    path.write_text("t,x,heave\n0,0,0\n1,0,0\n")
    with pytest.raises(MalformedDescription, match="heave"):
        base_motion.from_csv(path)
    path.write_text("t,x\n0,0\n1,zero\n")
    with pytest.raises(MalformedDescription, match="not a number"):
        base_motion.from_csv(path)
    path.write_text("t,x,roll\n0,0,0\n1,0,nan\n")
    with pytest.raises(MalformedDescription, match="row 2, column 'roll': nan is not finite"):
        base_motion.from_csv(path)


def test_carried_law_puts_the_carrier_where_the_law_says(load_cached):
    """The root joints' values give the carrier's position and R = Rz(yaw) Ry(pitch) Rx(roll); their
    rates its world angular velocity, the log of R(t+h) R(t-h)^T / 2h."""
    mech = with_base(load_cached("spherical_2dof"), "moving")
    t = np.linspace(0, 3, 7)
    law = base_motion.carried(mech, base_motion.from_callable(_law, t))
    assert law.names[6:] == ("r11", "r21")
    frame, data = mech.model.getFrameId(CARRIER_FRAME), mech.model.createData()
    q = mech.home_q.copy()
    h = 1e-6
    for k, x in enumerate(t):
        q[:6], v = law.values[k, :6], np.r_[law.rates[k, :6], np.zeros(mech.model.nv - 6)]
        pin.forwardKinematics(mech.model, data, q, v)
        placement = pin.updateFramePlacement(mech.model, data, frame)
        x_, y_, z_, roll, pitch, yaw = _pose(x)
        np.testing.assert_allclose(placement.translation, [x_, y_, z_], atol=1e-15)
        np.testing.assert_allclose(placement.rotation, pin.rpy.rpyToMatrix(roll, pitch, yaw), atol=1e-15)
        after, before = pin.rpy.rpyToMatrix(*_pose(x + h)[3:]), pin.rpy.rpyToMatrix(*_pose(x - h)[3:])
        omega = pin.log3(after @ before.T) / (2 * h)
        twist = pin.getFrameVelocity(mech.model, data, frame, pin.LOCAL_WORLD_ALIGNED)
        np.testing.assert_allclose(twist.angular, omega, atol=1e-8)


def test_carried_refuses_a_fixed_base_and_other_times(load_cached):
    fixed = load_cached("spherical_2dof")
    motion = base_motion.from_callable(_law, np.linspace(0, 1, 5))
    with pytest.raises(InvalidArgument, match="mech"):
        base_motion.carried(fixed, motion)
    moving = with_base(fixed, "moving")
    other = base_motion.carried(moving, base_motion.from_callable(_law, np.linspace(0, 2, 5)))
    with pytest.raises(InvalidArgument, match="inputs"):
        base_motion.carried(moving, motion, other)
