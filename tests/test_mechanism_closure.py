"""`mechkit.mechanism_closure`: a mechanism's closure at one configuration, its rows' Jacobian and drift
against finite differences of the residual, and the assembly keeping the joints it is given."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest


@pytest.fixture
def four_bar(load_cached):
    return load_cached("four_bar")


def test_the_jacobian_and_the_drift_are_the_residuals_derivatives(four_bar):
    """de/dt = J v and d2e/dt2 = J a + gamma along q(t) = q + v t + a t^2 / 2 (revolute joints: q is
    a vector space), by central differences of `closure_residual`."""
    m = four_bar
    rng = np.random.default_rng(3)
    q, v, a = m.home_q, rng.standard_normal(m.model.nv), rng.standard_normal(m.model.nv)
    h = 1e-4

    def e(t):
        return m.closure_residual(pin.integrate(m.model, q, v * t + a * t * t / 2))

    J, gamma = m.closure_jacobian(q), m.closure_drift(q, v)
    assert np.max(np.abs((e(h) - e(-h)) / (2 * h) - J @ v)) < 1e-6
    assert np.max(np.abs((e(h) - 2 * e(0) + e(-h)) / h**2 - (J @ a + gamma))) < 1e-5


def test_solve_closure_keeps_the_fixed_joints_and_closes_the_loop(four_bar):
    m = four_bar
    start = m.home_q.copy()
    start[m.q_index("crank")] += 0.2
    start[m.q_index("rocker")] -= 0.1  # the loop opened
    solved = m.solve_closure(start, ["crank"])
    assert solved.q[m.q_index("crank")] == start[m.q_index("crank")]
    assert np.max(np.abs(m.closure_residual(solved.q))) < 1e-10
    again = m.assemble({"crank": float(start[m.q_index("crank")])}, guess=m.home_q)
    assert np.max(np.abs(again - solved.q)) < 1e-8


def test_the_mobility_is_the_jacobians_nullity(four_bar):
    m = four_bar
    mob = m.mobility(m.home_q)
    assert mob.dof == m.model.nv - np.linalg.matrix_rank(m.closure_jacobian(m.home_q)) == 1
    assert m.singularity(m.home_q) == pytest.approx(
        np.linalg.cond(np.delete(m.closure_jacobian(m.home_q), m.v_index("crank"), axis=1))
    )


def test_a_home_newton_closes_outside_the_limits_is_re_sought_inside_them():
    """Gepetto's delta robot: Newton from its joints' zero closes free2_rod1 at -2.78 rad, outside [-pi/2, pi/2]
    by more than whole turns; the home assembly is the one inside the file's limits, closed, on the same inputs."""
    from tests_support import FIXTURES

    import mechkit

    m = mechkit.load(FIXTURES / "field" / "gepetto" / "robot_delta" / "robot.urdf")
    home = m.home_assembly
    assert home.outside == () and home.branch.endswith("re-sought inside the limits")
    assert np.linalg.norm(m.closure_residual(home.q)) <= 1e-12
    i = m.model.joints[m.joint_id("free2_rod1")].idx_q
    assert -np.pi / 2 <= home.q[i] <= np.pi / 2
    for joint, value in m.spec.home(m.params).items():
        assert m.joint_values(home.q)[joint] == pytest.approx(value, abs=1e-12)
