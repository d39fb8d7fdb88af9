"""`mechkit.simulation.fixed_step`: the classic RK4 converges at order 4 and its dense output at order 3
on an equation with a closed-form solution; on the four-bar's free swing (the simulator's own loop:
projection after every step) its error against a converged adaptive run falls 16-fold per halved step;
it refuses to run without a step."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.simulation.fixed_step import RK4
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


def test_rk4_needs_a_fixed_step():
    with pytest.raises(InvalidParameters) as err:
        Options("RK4")
    assert err.value.name == "method" and "dt" in str(err.value)
    with pytest.raises(ValueError, match="fixed step"):
        RK4(lambda t, y: y, 0.0, np.ones(1), 1.0)
