"""`mechkit.simulation.integrator`: scipy's one-step methods restarted after every step, against exact
solutions; events located on the dense output; options refused by name; and a second method on a
mechanism's motion."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit import simulation
from mechkit.base.exceptions import InvalidParameters
from mechkit.simulation.integrator import first_crossing


def oscillator(t, y):
    """y'' = -y, as a first-order system."""
    return np.array([y[1], -y[0]])


@pytest.mark.parametrize("method", ["RK45", "DOP853", "RK23", "Radau"])
def test_restarted_steps_follow_the_exact_solution(method):
    """The harmonic oscillator from (1, 0) over 3 s, restarted after every step: cos and -sin at every
    sample to the tolerances' order."""
    times, states = simulation.run(oscillator, 0.0, np.array([1.0, 0.0]), 3.0, simulation.Options(method, 1e-10, 1e-12))
    t, y = np.array(times), np.array(states)
    assert t[0] == 0.0 and t[-1] == pytest.approx(3.0) and np.all(np.diff(t) > 0)
    assert np.max(np.abs(y[:, 0] - np.cos(t))) < 1e-7 and np.max(np.abs(y[:, 1] + np.sin(t))) < 1e-7


def test_a_fixed_step_takes_that_step_and_the_projection_acts_after_each():
    """dt = 0.01 over 0.1 s: ten steps of 0.01 s; a projection onto the unit circle keeps |y| = 1 exactly
    (the oscillator's invariant) after every step."""
    project = lambda t, y: y / np.linalg.norm(y)
    times, states = simulation.run(oscillator, 0.0, np.array([2.0, 0.0]), 0.1, simulation.Options(dt=0.01), project)
    assert np.allclose(np.diff(times), 0.01, rtol=1e-12) and len(times) == 11
    assert np.allclose(np.linalg.norm(states, axis=1), 1.0, atol=1e-15)


def test_the_earliest_crossing_in_its_direction_is_located():
    """Adaptive steps of the oscillator from (1, 0): the first step in which y0 = cos t falls through 0 locates
    the crossing at pi / 2 on its dense output; a rising event on the same function is not reported there,
    and of two crossings in one step the earlier wins."""
    stepper = simulation.Stepper(oscillator, 3.0, simulation.Options(rtol=1e-11, atol=1e-13))
    falling = simulation.Event("cos", lambda t, y: y[0], -1)
    rising = simulation.Event("cos rising", lambda t, y: y[0], 1)
    t, y, hit = 0.0, np.array([1.0, 0.0]), None
    while hit is None:
        stepper.restart(t, y)
        t1, y1 = stepper.step()
        hit = first_crossing([rising, falling], stepper.dense(), t, y, t1, y1)
        t0, y0, t, y = t, y, t1, y1
    assert hit[0] == 1 and hit[1] == pytest.approx(np.pi / 2, abs=1e-9)
    nearer = simulation.Event("half the step's first value", lambda s, x, c=y0[0] / 2: x[0] - c, -1)
    k, te = first_crossing([falling, nearer], stepper.dense(), t0, y0, t, y)
    assert k == 1 and t0 < te < hit[1]


@pytest.mark.parametrize(
    "options, name", [({"method": "BDF"}, "method"), ({"dt": -1.0}, "dt"), ({"rtol": 0.0}, "rtol/atol/max_step")]
)
def test_bad_options_are_refused_by_name(options, name):
    with pytest.raises(InvalidParameters) as err:
        simulation.Options(**options)
    assert err.value.name == name


def test_a_step_that_cannot_be_taken_says_when():
    """A solution that blows up at t = 1 (y' = y^2 from 1): the step size collapses before it, reported with the
    time."""
    with pytest.raises(simulation.IntegrationFailed, match="the integrator stopped at t = ") as err:
        simulation.run(lambda t, y: y**2, 0.0, np.array([1.0]), 2.0, simulation.Options())
    assert 0.99 < err.value.t <= 1.0


def test_a_second_integrator_agrees(four_bar, free):
    """DOP853 at a hundred times tighter tolerances follows the same motion."""
    other = four_bar.simulate(1.0, method="DOP853", rtol=1e-11, atol=1e-13, reactions=False)
    assert np.max(np.abs(other.motion.q[-1] - free.motion.q[-1])) < 1e-6
    assert other.energy_error <= 1e-8 * other.energy_scale


def test_radau_keeps_its_solver_across_restarts_at_its_own_step_s_end():
    """Radau restarted where its step ended keeps its solver (its Jacobian, factors and step history: fewer
    Jacobians than steps) and takes the state given; restarted elsewhere (an event's time) it builds a new one."""
    calls = []

    def jacobian(t, y):
        calls.append(t)
        return np.array([[0.0, 1.0], [-1.0, 0.0]])

    stepper = simulation.Stepper(oscillator, 3.0, simulation.Options("Radau", 1e-8, 1e-10), lambda: jacobian)
    t, y = 0.0, np.array([1.0, 0.0])
    stepper.restart(t, y)
    solver, steps = stepper.solver, 0
    while t < 3.0:
        t, y = stepper.step()
        y = y / np.linalg.norm(y)  # a projection onto the oscillator's invariant circle
        steps += 1
        if t < 3.0:
            stepper.restart(t, y)
            assert stepper.solver is solver and np.array_equal(stepper.solver.y, y)
    assert abs(y[0] - np.cos(3.0)) < 1e-6 and steps > 5 and len(calls) < steps
    stepper.restart(1.5, np.array([np.cos(1.5), -np.sin(1.5)]))
    assert stepper.solver is not solver and stepper.solver.t == 1.5
