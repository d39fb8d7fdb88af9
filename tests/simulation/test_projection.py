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
