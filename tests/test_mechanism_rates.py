"""`mechkit.mechanism_rates`: velocities and accelerations from the inputs against finite differences of
assemblies along the input, one sample and N at once."""

from __future__ import annotations

import numpy as np
import pytest


@pytest.fixture
def four_bar(load_cached):
    return load_cached("four_bar")


def _assembled(m, crank: float) -> np.ndarray:
    return m.assemble({"crank": crank}, guess=m.home_q)


def test_velocities_and_accelerations_are_the_assemblies_derivatives(four_bar):
    """The crank turning at a constant rate w: v = dq/dt and a = d2q/dt2 of the assembled q(t), by
    central differences of the assembly (an independent route: Newton on positions only)."""
    m = four_bar
    crank, w, h = float(m.home_q[m.q_index("crank")]), 1.3, 1e-4
    q = _assembled(m, crank)
    ahead, behind = _assembled(m, crank + w * h), _assembled(m, crank - w * h)
    v = m.velocities(q, [w])
    a = m.accelerations(q, v, {"crank": 0.0})
    assert np.max(np.abs(m.closure_jacobian(q) @ v)) < 1e-12
    assert v[m.v_index("crank")] == pytest.approx(w, abs=1e-15)
    assert np.max(np.abs((ahead - behind) / (2 * h) - v)) < 1e-6
    assert np.max(np.abs((ahead - 2 * q + behind) / h**2 - a)) < 1e-4
    assert m.second_order_inconsistency(q, v) < 1e-10


def test_the_batches_give_the_numbers_of_one_sample_at_a_time(four_bar):
    m = four_bar
    Q = np.array([_assembled(m, c) for c in (0.3, 0.6, 0.9)])
    rates, accs = np.array([[0.5], [-1.0], [2.0]]), np.array([[0.1], [0.0], [-0.4]])
    V = m.velocities_batch(Q, rates)
    A = m.accelerations_batch(Q, V, {"crank": accs[:, 0]})
    for k in range(len(Q)):
        np.testing.assert_allclose(V[k], m.velocities(Q[k], rates[k]), rtol=0, atol=1e-12)
        np.testing.assert_allclose(A[k], m.accelerations(Q[k], V[k], accs[k]), rtol=0, atol=1e-12)
