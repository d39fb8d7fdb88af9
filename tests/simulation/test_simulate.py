"""`mechkit.simulation.simulate`: a free motion's own checks (the energy balance, the closure), given torques
whose work is integrated with the motion, and bad options refused by name."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.integrate

from mechkit import forces, simulation
from mechkit.base.exceptions import InvalidParameters


def test_conservative_energy_balance_and_closure(free):
    """No force but gravity: kinetic + potential stays constant to 1e-6 of the energy exchanged (measured
    2e-9), the loop stays closed to 1e-10 m (measured 1e-12), and nothing is supplied or dissipated."""
    assert free.energy_scale > 0.2  # J: the coupler swings through
    assert free.energy_error <= 1e-6 * free.energy_scale
    assert free.residual.max() <= 1e-10
    assert np.all(free.supplied == 0) and np.all(free.dissipated == 0)


def test_given_torque_supplies_the_integral_of_its_power(four_bar):
    """A constant 0.5 N m on the crank (a torque motor without envelope): the work supplied, integrated
    beside the motion, equals the quadrature of 0.5 x the crank's rate over the samples, and the balance closes."""
    run = four_bar.simulate(0.3, torques={"crank": 0.5}, reactions=False)
    assert run.element_names[-1] == "crank" and run.roles[-1] == "source"
    rate = run.motion.v[:, four_bar.v_index("crank")]
    quadrature = scipy.integrate.simpson(0.5 * rate, x=run.t)
    assert abs(run.supplied[-1]) > 1e-3
    assert run.supplied[-1] == pytest.approx(quadrature, rel=1e-5)
    assert run.energy_error <= 1e-6 * run.energy_scale and run.residual.max() <= 1e-10


@pytest.mark.parametrize(
    "options, name",
    [
        ({"duration": -1.0}, "duration"),
        ({"duration": float("nan")}, "duration"),
        ({"method": "Euler"}, "method"),
        ({"dt": 0.0}, "dt"),
    ],
)
def test_bad_options_are_refused_by_name(four_bar, options, name):
    duration = options.pop("duration", 0.1)
    with pytest.raises(InvalidParameters) as err:
        simulation.simulate(four_bar, duration, **options)
    assert err.value.name == name


def test_two_elements_of_one_name_are_refused(four_bar):
    a = forces.CoulombFriction(four_bar.model, {"crank": 0.1}, name="f")
    b = forces.CoulombFriction(four_bar.model, {"rocker": 0.1}, name="f")
    with pytest.raises(InvalidParameters) as err:
        simulation.simulate(four_bar, 0.1, forces=[a, b])
    assert err.value.name == "forces"


def test_an_unknown_latch_joint_is_refused(four_bar):
    with pytest.raises(InvalidParameters, match="nowhere"):
        simulation.simulate(four_bar, 0.1, latches=[simulation.Latch("nowhere", 0.0)])
