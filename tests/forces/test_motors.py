"""`mechkit.forces.motors`: a commanded effort clipped to a DC motor's torque-speed line."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechkit import forces
from mechkit.base.exceptions import InvalidParameters

from .states import state


def test_torque_motor_envelope():
    assert forces.envelope(5.0, 0.0, 2.0, 10.0) == 2.0  # stall
    assert forces.envelope(5.0, 5.0, 2.0, 10.0) == pytest.approx(1.0)  # half the no-load rate: half the stall
    assert forces.envelope(-5.0, 5.0, 2.0, 10.0) == pytest.approx(-3.0)  # braking against the motion
    assert forces.envelope(0.5, 5.0, math.inf, 10.0) == 0.5


def test_a_joint_motor_acts_at_its_joint_and_supplies_effort_times_rate(four_bar):
    """On the crank, commanded 3 t N m within a stall of 1 N m at rest: the effort is the command inside
    the envelope and the clipped value outside it, at the crank's column only; the power is effort * rate."""
    m = four_bar
    motor = forces.TorqueMotor.on_joint(m.model, "crank", lambda t: 3.0 * t, stall=1.0, no_load=6.0)
    assert motor.name == "crank" and motor.role == "source"
    for t in (0.1, 2.0):
        s = state(m, t=t)
        rate = s.v[m.v_index("crank")]
        load = motor.load(s)
        expected = min(max(3.0 * t, -(1 + rate / 6.0)), 1 - rate / 6.0)
        assert load.generalized[m.v_index("crank")] == pytest.approx(expected, rel=1e-14)
        assert np.count_nonzero(load.generalized) == 1
        assert load.power == pytest.approx(expected * rate, rel=1e-14)


def test_bad_motors_are_refused_by_name(four_bar):
    with pytest.raises(InvalidParameters, match="motor m"):
        forces.TorqueMotor(np.ones(3), 1.0, stall=0.0, name="m")
    with pytest.raises(InvalidParameters, match="nowhere"):
        forces.TorqueMotor.on_joint(four_bar.model, "nowhere", 1.0)
