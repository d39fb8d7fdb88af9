"""A mechanism of one velocity coordinate (tests/fixtures/pendulum.urdf: a 1 kg rod of 1 m on one pivot):
Pinocchio hands a 6 x 1 Jacobian over as a vector of 6 and an empty constraint Jacobian as a vector, which
used to break loading, forward dynamics, reactions in a simulation, stiffness and modes. Each is checked
against the pendulum's closed form."""

from __future__ import annotations

import numpy as np
import pytest
from tests_support import FIXTURES, run_mechkit

import mechkit
from mechkit.elastic import ElasticModel

PENDULUM = FIXTURES / "pendulum.urdf"
G = 9.81
MASS, CENTRE, IYY = 1.0, 0.5, 0.084  # kg, m from the pivot, kg m^2 about the centre of mass (the file's)
PIVOT_INERTIA = IYY + MASS * CENTRE**2
E, GJ, I = 7e10, 2.6e10 * 2e-9, 1e-9  # the file's beam: Pa, N m^2, m^4


@pytest.fixture(scope="module")
def pendulum():
    return mechkit.load(PENDULUM)


def _accel(theta: float, tau: float) -> float:
    """The rod's angular acceleration at angle theta above the horizontal under a pivot torque tau."""
    return (tau - MASS * G * CENTRE * np.cos(theta)) / PIVOT_INERTIA


@pytest.mark.parametrize("method", mechkit.core.FORWARD_METHODS)
def test_forward_dynamics_is_the_closed_form(pendulum, method):
    q, v, tau = np.array([0.3]), np.array([1.2]), np.array([0.7])
    a = pendulum.forward_dynamics(q, v, tau, method=method).a
    assert a[0] == pytest.approx(_accel(0.3, 0.7), rel=1e-9)


def test_inverse_dynamics_holds_the_rod_and_the_pivot_carries_its_weight(pendulum):
    out = pendulum.inverse_dynamics(np.zeros(1), np.zeros(1), np.zeros(1))
    assert out.efforts["pivot"] == pytest.approx(MASS * G * CENTRE, rel=1e-12)
    assert out.reactions["pivot"].wrench[2] == pytest.approx(MASS * G, rel=1e-12)


def test_a_simulated_swing_keeps_its_energy(pendulum):
    run = pendulum.simulate(0.5)
    assert run.motion.q[-1, 0] < -0.5  # released horizontal, it falls
    assert run.energy_error <= 1e-6 * run.energy_scale


def test_stiffness_and_modes_of_the_rod_as_a_cantilever(pendulum):
    """With the pivot's actuator locked the rod is a cantilever clamped at the pivot, the beam ending at
    its centre of mass (docs/elastic.md): at that point 3 E I / L^3 across, G J / L in torsion."""
    e = ElasticModel(pendulum)
    k = e.stiffness(pendulum.home_q, "rod", np.array([CENTRE, 0.0, 0.0])).free
    assert k[1] == pytest.approx(3 * E * I / CENTRE**3, rel=1e-9)
    assert k[3] == pytest.approx(GJ / CENTRE, rel=1e-9)
    assert np.all(np.isfinite(e.modes(pendulum.home_q, 2).frequencies))


def test_the_commands_answer():
    for args in (["report"], ["simulate", "--duration", "0.2"], ["modes", "-n", "2"]):
        out = run_mechkit(args[0], str(PENDULUM), *args[1:])
        assert out.returncode == 0 and "Traceback" not in out.stderr, out.stderr


def test_validate_of_the_pendulum_is_refused_in_one_line():
    """No loop, nothing to cross-check: one line, exit 2 (it used to be a numpy traceback from loading)."""
    out = run_mechkit("validate", str(PENDULUM))
    assert out.returncode == 2 and "has no loop closure" in out.stderr and "Traceback" not in out.stderr
