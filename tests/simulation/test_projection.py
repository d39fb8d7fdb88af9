"""`mechkit.simulation.projection`: a state put back on the closures and drives by the smallest change:
positions closed to the tolerance with the driven joints on their law, velocities the orthogonal
projection onto the closures' null space (against scipy's null-space basis)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from mechkit import simulation


def test_positions_close_the_loop_with_the_driven_joints_on_their_law(four_bar):
    """Home disturbed by 0.05 rad everywhere: without drives the loop closes to the tolerance; with the crank
    held at 0.7 rad the pose is the assembly at that crank angle."""
    m = four_bar
    p = simulation.Projection(m)
    off = m.home_q + 0.05
    q = p.positions(off, simulation.Drives(), 0.0)
    assert p.residual(off) > 1e-3 and p.residual(q) <= simulation.POSITION_TOL
    # one product gives the residual and the Jacobian: the core's residual to rounding
    assert p.residual(q) == pytest.approx(float(np.max(np.abs(m.closure_residual(q)))), abs=1e-15)
    assert p.residual(off) == pytest.approx(float(np.max(np.abs(m.closure_residual(off)))), rel=1e-12)
    held = p.positions(off, simulation.Drives(held={"crank": 0.7}), 0.0)
    assert held[m.q_index("crank")] == 0.7 and p.residual(held) <= simulation.POSITION_TOL
    assert np.allclose(held, m.assemble([0.7], guess=off), atol=1e-10)


def test_velocities_are_the_orthogonal_projection_onto_the_closures(four_bar):
    """Without drives: v - J^+ J v, i.e. N N^T v with N an orthonormal basis of J's null space; with the
    crank on a law of rate 1.3 rad/s: the one-freedom motion at that rate."""
    m = four_bar
    p = simulation.Projection(m)
    q = m.assemble([0.9])
    v = np.random.default_rng(5).normal(size=m.model.nv)
    N = scipy.linalg.null_space(m.closure_jacobian(q))
    assert np.allclose(p.velocities(q, v, simulation.Drives(), 0.0), N @ (N.T @ v), atol=1e-12)
    law = simulation.Drives(("crank",), lambda t: (np.array([0.9]), np.array([1.3]), np.array([0.0])))
    assert np.allclose(p.velocities(q, v, law, 0.0), m.velocities(q, [1.3]), atol=1e-12)


@pytest.mark.parametrize(("method", "dt"), [("RK4", 3e-4), ("SymplecticEuler", 1e-3), ("RK45", None)])
def test_the_closure_holds_at_every_sample_though_small_drifts_are_left(four_bar, method, dt):
    """Free swing for 1 s: a state whose drift is within `DRIFT_TOL` is not projected (RK4 at MuJoCo's step
    drifts by about 1e-15 m a step: the residual grows past rounding), and every recorded sample is closed
    to `DRIFT_TOL` <= 1e-10 m, the simulation's promise; the residual recorded is the core's."""
    run = four_bar.simulate(1.0, method=method, dt=dt, reactions=False)
    assert simulation.DRIFT_TOL <= 1e-10 and run.residual.max() <= simulation.DRIFT_TOL
    some = np.linspace(0, len(run.t) - 1, 7).astype(int)
    core_residual = [float(np.max(np.abs(four_bar.closure_residual(run.motion.q[i])))) for i in some]
    assert np.allclose(run.residual[some], core_residual, rtol=1e-9, atol=1e-15)
    if method == "RK4":
        assert run.residual.max() > 100 * np.finfo(float).eps  # the small drift was left, not polished away
