"""`mechkit.forces.gravity`: another gravity than the model's, its load and its potential."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit import forces
from mechkit.base.exceptions import InvalidParameters

from .states import state


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
        m.model, m.model.createData(), s.q
    )
    assert np.allclose(tau, expected, atol=1e-12)
    total = pin.computePotentialEnergy(m.model, m.model.createData(), s.q) + element.energy(m.model, s.data, s.q)
    assert total == pytest.approx(pin.computePotentialEnergy(other, other.createData(), s.q), abs=1e-12)


def test_the_models_own_gravity_adds_nothing(four_bar):
    """Gravity equal to the model's: no load, no potential."""
    m = four_bar
    element = forces.Gravity(m.model, m.model.gravity.linear)
    s = state(m)
    assert np.all(element.load(s).wrenches == 0.0) and element.energy(m.model, s.data, s.q) == 0.0


@pytest.mark.parametrize("g", [(0.0, 0.0), (0.0, np.nan, -9.81)])
def test_bad_gravity_is_refused_by_name(four_bar, g):
    with pytest.raises(InvalidParameters) as err:
        forces.Gravity(four_bar.model, g)
    assert err.value.name == "g"
