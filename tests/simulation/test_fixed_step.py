"""`mechkit.simulation.fixed_step`: the classic RK4 converges at order 4 and its dense output at order 3
on an equation with a closed-form solution; on the four-bar's free swing (the simulator's own loop:
projection after every step) its error against a converged adaptive run falls 16-fold per halved step,
semi-implicit Euler's 2-fold (order 1) and the implicit midpoint's 4-fold (order 2); the midpoint rule
stays stable on a stiff equation where RK4 blows up; a method without its step or position part is
refused."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.simulation.fixed_step import RK4, ImplicitMidpoint, SymplecticEuler
from mechkit.simulation.integrator import Options


def _exact(t):
    """y' = -y + sin t, y(0) = 1: y = 1.5 e^-t + (sin t - cos t) / 2."""
    return 1.5 * np.exp(-t) + 0.5 * (np.sin(t) - np.cos(t))


def _run(h, t_end=2.0):
    solver = RK4(lambda t, y: -y + np.sin(t), 0.0, np.array([1.0]), t_end, max_step=h)
    ends, mids = [], []
    while solver.status == "running":
        solver.step()
        dense = solver.dense_output()
        mid = 0.5 * (dense.t_old + dense.t)
        ends.append(abs(float(solver.y[0]) - _exact(solver.t)))
        mids.append(abs(float(dense(mid)[0]) - _exact(mid)))
    return max(ends), max(mids), solver.t


def test_rk4_is_fourth_order_and_its_dense_output_third_order():
    (end1, mid1, t1), (end2, mid2, t2) = _run(0.1), _run(0.05)
    assert t1 == t2 == 2.0
    assert 2**4 * 0.8 < end1 / end2 < 2**4 * 1.2
    assert 2**3 * 0.7 < mid1 / mid2 < 2**4 * 1.2  # at least third order between the step's ends
    assert end2 < 1e-7


def test_the_last_step_is_shortened_to_end_on_time():
    *_, t = _run(0.3, t_end=1.0)
    assert t == 1.0


def test_rk4_on_the_four_bar_converges_at_order_four(four_bar):
    """Free swing for 0.2 s: crank angle at the end against DOP853 at rtol 1e-12."""
    crank = four_bar.q_index("crank")
    reference = four_bar.simulate(0.2, method="DOP853", rtol=1e-12, atol=1e-13, reactions=False)
    errors = []
    for dt in (4e-3, 2e-3):
        run = four_bar.simulate(0.2, method="RK4", dt=dt, reactions=False)
        assert run.t[-1] == pytest.approx(0.2) and run.residual.max() <= 1e-10
        errors.append(abs(run.motion.q[-1, crank] - reference.motion.q[-1, crank]))
    assert errors[1] < 1e-6 and 2**4 * 0.6 < errors[0] / errors[1] < 2**4 * 1.4, errors


@pytest.mark.parametrize(
    ("method", "order", "steps"), [("SymplecticEuler", 1, (2e-3, 1e-3)), ("ImplicitMidpoint", 2, (4e-3, 2e-3))]
)
def test_the_other_fixed_step_methods_converge_at_their_order_on_the_four_bar(four_bar, method, order, steps):
    """Free swing for 0.2 s, crank angle at the end against DOP853 at rtol 1e-12 (measured: ratios 2.009 and
    4.003; closure <= 1e-10 m at every sample)."""
    crank = four_bar.q_index("crank")
    reference = four_bar.simulate(0.2, method="DOP853", rtol=1e-12, atol=1e-13, reactions=False)
    errors = []
    for dt in steps:
        run = four_bar.simulate(0.2, method=method, dt=dt, reactions=False)
        assert run.t[-1] == pytest.approx(0.2) and run.residual.max() <= 1e-10
        errors.append(abs(run.motion.q[-1, crank] - reference.motion.q[-1, crank]))
    assert 2**order * 0.9 < errors[0] / errors[1] < 2**order * 1.1, errors


def _oscillator(solver_class, h, t_end=2.0, **extra):
    """x'' = -x from x = 1 at rest: the largest error of x against cos t, and the energy's largest change."""
    solver = solver_class(lambda t, y: np.array([y[1], -y[0]]), 0.0, np.array([1.0, 0.0]), t_end, max_step=h, **extra)
    error = energy = 0.0
    while solver.status == "running":
        solver.step()
        error = max(error, abs(solver.y[0] - np.cos(solver.t)))
        energy = max(energy, abs(0.5 * (solver.y @ solver.y) - 0.5))
    return error, energy


def test_symplectic_euler_and_the_midpoint_rule_on_the_harmonic_oscillator():
    """Orders 1 and 2 against the closed form; over 200 periods semi-implicit Euler's energy error stays
    bounded at O(h) (symplectic: no drift) and the midpoint rule keeps the quadratic energy to rounding."""
    (e1, _), (e2, _) = _oscillator(SymplecticEuler, 0.02, npos=1), _oscillator(SymplecticEuler, 0.01, npos=1)
    assert 2 * 0.8 < e1 / e2 < 2 * 1.2
    (m1, _), (m2, _) = _oscillator(ImplicitMidpoint, 0.02), _oscillator(ImplicitMidpoint, 0.01)
    assert 4 * 0.9 < m1 / m2 < 4 * 1.1
    _, drift = _oscillator(SymplecticEuler, 0.01, t_end=400 * np.pi, npos=1)
    assert drift < 0.01  # h / 2 bounds the modified energy's distance
    _, kept = _oscillator(ImplicitMidpoint, 0.05, t_end=400 * np.pi)
    assert kept < 1e-10


def test_the_midpoint_rule_is_stable_on_a_stiff_equation_where_rk4_is_not():
    """y' = -1000 (y - cos t): at h = 0.01 (h lambda = -10, outside RK4's stability interval of -2.79) RK4's
    error grows without bound while the A-stable midpoint rule follows the slow solution to 1e-4."""

    def fun(t, y):
        return -1000.0 * (y - np.cos(t))

    def last_error(solver):
        while solver.status == "running":
            solver.step()
        slow = (1e6 * np.cos(1.0) + 1e3 * np.sin(1.0)) / (1e6 + 1)  # the particular solution at t = 1
        return abs(float(solver.y[0]) - slow)

    assert last_error(ImplicitMidpoint(fun, 0.0, np.array([np.cos(0.0)]), 1.0, max_step=0.01)) < 1e-4
    assert last_error(RK4(fun, 0.0, np.array([np.cos(0.0)]), 1.0, max_step=0.01)) > 1e10


def test_symplectic_euler_needs_its_position_part():
    with pytest.raises(InvalidParameters) as err:
        Options("SymplecticEuler", dt=1e-3)
    assert err.value.name == "method" and "npos" in str(err.value)
    with pytest.raises(ValueError, match="position part"):
        SymplecticEuler(lambda t, y: y, 0.0, np.ones(3), 1.0, max_step=0.1, npos=2)


def test_rk4_needs_a_fixed_step():
    with pytest.raises(InvalidParameters) as err:
        Options("RK4")
    assert err.value.name == "method" and "dt" in str(err.value)
    with pytest.raises(ValueError, match="fixed step"):
        RK4(lambda t, y: y, 0.0, np.ones(1), 1.0)
