"""A position servo of a given bandwidth: its gains, its refusals, and the step response of the driven
platform against the second-order loop it is tuned to be."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidArgument, InvalidParameters
from mechkit.bases import with_base
from mechkit.bases.servo import PositionServo, reflected_inertia

ZETA, BANDWIDTH = 0.7, 2 * np.pi * 3.0  # rad/s (ours)


@pytest.fixture(scope="module")
def weightless(load_cached):
    """The platform with no gravity and 0.05 kg m^2 rotors (its own model: the armature is ours to set)."""
    mech = with_base(load_cached("spherical_2dof"), "fixed", gravity=(0, 0, 0))
    for joint in mech.actuated:
        mech.model.armature[mech.v_index(joint)] = 0.05
    return mech


def test_gains_from_bandwidth(weightless):
    servo = PositionServo.with_bandwidth(weightless, "r11", lambda t: (0.0, 0.0), BANDWIDTH, ZETA)
    m = reflected_inertia(weightless, "r11")
    assert servo.kp == pytest.approx(m * BANDWIDTH**2) and servo.kd == pytest.approx(2 * ZETA * m * BANDWIDTH)
    assert servo.effort(0.0, np.full(weightless.model.nq, 0.1), np.full(weightless.model.nv, 1.0)) == pytest.approx(
        -0.1 * servo.kp - servo.kd
    )


def test_step_response_is_the_tuned_loop(weightless):
    """Released 0.01 rad off its command, each input returns as e0 e^(-zeta w t)(cos w_d t + zeta/sqrt(1-zeta^2)
    sin w_d t), to 5 % of e0 (the two inputs' coupling through the platform is the rest)."""
    home = weightless.spec.home(weightless.params)
    servos = [PositionServo.with_bandwidth(weightless, j, lambda t, x=home[j]: (x, 0.0), BANDWIDTH, ZETA) for j in home]
    start = weightless.assembly({j: x + 0.01 for j, x in home.items()}).q
    result = weightless.simulate(0.3, forces=servos, q0=start, dynamics="kkt", rtol=1e-8, atol=1e-10, reactions=False)
    t = result.t
    wd = BANDWIDTH * np.sqrt(1 - ZETA**2)
    expected = 0.01 * np.exp(-ZETA * BANDWIDTH * t) * (np.cos(wd * t) + ZETA / np.sqrt(1 - ZETA**2) * np.sin(wd * t))
    for joint in home:
        error = result.motion.q[:, weightless.q_index(joint)] - home[joint]
        assert np.abs(error - expected).max() < 5e-4


def test_refusals(weightless):
    with pytest.raises(InvalidArgument, match="kp"):
        PositionServo(weightless.model, "r11", lambda t: (0.0, 0.0), 0.0, 1.0)
    with pytest.raises(InvalidArgument, match="bandwidth"):
        PositionServo.with_bandwidth(weightless, "r11", lambda t: (0.0, 0.0), -1.0)
    with pytest.raises(InvalidParameters):
        PositionServo(weightless.model, "nowhere", lambda t: (0.0, 0.0), 1.0, 1.0)
