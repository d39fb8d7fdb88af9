"""`mechkit.simulation.small_oscillations`: the IFToMM four-bar with a diagonal spring against its closed form
(a rhombus of one freedom) and the published equilibrium, the linear solution against a nonlinear simulation,
a pose the held joints fix, and bad input."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit import load
from mechkit.base.exceptions import InvalidArgument
from mechkit.bench import iftomm_spring
from mechkit.simulation.small_oscillations import small_oscillations

FIXTURE = iftomm_spring.FIXTURE


@pytest.fixture(scope="module")
def spring_four_bar():
    return load(str(FIXTURE))


def test_equilibrium_and_eigenvalues_equal_the_closed_form(spring_four_bar):
    """The equilibrium (the strut read from the file by default) is the rhombus at the closed form's angle to
    1e-12 rad and within 5e-11 rad of the benchmark's published twelve digits; the eigenvalues equal the
    closed form's roots to 1e-8 relative (the reduced stiffness is a central difference)."""
    m = spring_four_bar
    phi, roots = iftomm_spring.closed_form()
    eq = m.equilibrium()
    rocker, crank = eq.q[m.q_index("rocker")], eq.q[m.q_index("crank")]
    assert rocker == pytest.approx(phi, abs=1e-12) and crank == pytest.approx(phi, abs=1e-12)
    assert abs(rocker - iftomm_spring.PUBLISHED_PHI) < 5e-11
    osc = small_oscillations(m, eq)
    assert np.allclose(osc.eigenvalues, roots, rtol=1e-8, atol=0)
    assert osc.damping_ratios[0] == pytest.approx(-roots[1].real / abs(roots[1]), rel=1e-8)


def test_linear_solution_follows_the_nonlinear_simulation(spring_four_bar):
    """Released from the equilibrium with a small crank rate w0, the simulated crank angle follows the linear
    solution w0 / wd exp(sigma t) sin(wd t) over 5 s, and its departure from it is quadratic in w0 (the
    nonlinearity's; a wrong eigenvalue would leave one linear in w0): measured 2.7e-9 and 2.7e-11 rad."""
    m = spring_four_bar
    eq = m.equilibrium()
    osc = small_oscillations(m, eq)
    sigma, wd = osc.eigenvalues[-1].real, osc.eigenvalues[-1].imag
    u = eq.basis[:, 0] / eq.basis[m.v_index("crank"), 0]  # the free motion with a unit crank rate
    crank = m.q_index("crank")
    errors = []
    for w0 in (1e-4, 1e-5):
        run = m.simulate(5.0, q0=eq.q, v0=w0 * u, reactions=False, rtol=1e-11, atol=1e-13)
        t = run.motion.t
        linear = eq.q[crank] + w0 / wd * np.exp(sigma * t) * np.sin(wd * t)
        errors.append(np.max(np.abs(run.motion.q[:, crank] - linear)))
        assert errors[-1] < 10 * (w0 / wd) ** 2
    assert 80 < errors[0] / errors[1] < 120


def test_a_pose_the_held_joints_fix_has_no_eigenvalue(spring_four_bar):
    eq = spring_four_bar.equilibrium({"crank": 2.2})
    osc = small_oscillations(spring_four_bar, eq)
    assert osc.eigenvalues.shape == (0,) and osc.basis.shape == (3, 0)


def test_bad_input_is_refused_by_name(spring_four_bar):
    with pytest.raises(InvalidArgument, match="eq"):
        small_oscillations(spring_four_bar, spring_four_bar.home_q)
    with pytest.raises(InvalidArgument, match=r"elements\[0\]"):
        small_oscillations(spring_four_bar, spring_four_bar.equilibrium(), elements=["spring"])
