"""`mechkit.forces.coulomb`: constant joint friction, regularised by tanh near zero speed; it only dissipates."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechkit import forces
from mechkit.base.exceptions import InvalidParameters

from .states import state


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


def test_power_is_the_efforts_times_the_rates_and_never_positive(four_bar):
    """At rates on both sides of the threshold and of both signs, the power is sum effort * rate (<= 0), and
    the smooth sign is odd and within [-1, 1]."""
    m = four_bar
    f = forces.CoulombFriction(m.model, {"crank": 0.3, "rocker": 0.05}, threshold=0.02)
    q = m.assemble([0.9])
    for rate in (-3.0, -0.01, 1e-4, 0.02, 2.0):
        s = state(m, q=q, v=m.velocities(q, [rate]))
        load = f.load(s)
        assert load.power == pytest.approx(float(load.generalized @ s.v), rel=1e-12, abs=1e-300)
        assert load.power <= 0.0
    x = np.linspace(-1.0, 1.0, 41)
    assert np.allclose(forces.smooth_sign(x, 0.1), -forces.smooth_sign(-x, 0.1))
    assert np.all(np.abs(forces.smooth_sign(x)) <= 1.0)
    assert forces.smooth_sign(0.1, 0.1) == pytest.approx(math.tanh(1.0))


def test_bad_friction_is_refused_by_name(four_bar):
    """An unknown joint, a negative size: each named."""
    with pytest.raises(InvalidParameters, match="nowhere"):
        forces.CoulombFriction(four_bar.model, {"nowhere": 0.1})
    with pytest.raises(InvalidParameters, match="friction on crank"):
        forces.CoulombFriction(four_bar.model, {"crank": -0.1})
