"""The exact forward dynamics without bounds (`mechkit.core.dense_forward`): its accelerations against the
dense KKT and the SVD's null space on the truss and two small mechanisms, every row closed; a state with
no rigid answer and a change of rank handed to the bounded path, which refuses or solves as before."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pinocchio as pin
import pytest

from mechkit import core
from mechkit.base.exceptions import InconsistentMotion, MechkitError
from mechkit.bench.sampling import make_samples
from mechkit.core import dense_forward, forward, null_space

from .no_rigid_answer import inconsistent_state
from .test_determinacy import _five_bar_fold

TOL = forward.ACCELERATION_TOL


def _solve(cm, cd, q, v, tau):
    """The rows, drift and the fast solve's accelerations at a state (the partition chosen there if none)."""
    J, gamma, _ = forward._rows_and_drift(cm, cd, q, v, None)
    if cd.partition is None:
        null_space.partitioned_null_space(cd, J, gamma)
    M, f = pin.crba(cm.model, cd.pin, q), tau - pin.nonLinearEffects(cm.model, cd.pin, q, v)
    return J, gamma, dense_forward.solve(cd, J, gamma, 0.0, M, f, TOL)


@pytest.mark.parametrize("name", ["four_bar", "parallel_2t1r", "deployable_9rr12uru"])
def test_the_accelerations_are_the_kkt_s_and_the_svd_s_and_close_every_row(name, load_cached):
    """At random consistent states (the bench's: assembled, random input rates; the truss has a redundant
    row) the fast solve, with the partition of the first state, gives the dense KKT's accelerations and
    those of the SVD's orthonormal null space to 1e-10 relative, closes every row (J a + gamma) to 1e-10 of
    its terms, and is what the exact method returns."""
    m = load_cached(name)
    cm, cd = m.closure_model, m.closure_model.create_data()
    for s in make_samples(m, 4):
        J, gamma, a = _solve(cm, cd, s.q, s.v, s.tau)
        assert a is not None
        scale = np.abs(a).max()
        kkt = core.forward_dynamics(cm, cm.create_data(), s.q, s.v, s.tau, "kkt").a
        M = pin.crba(cm.model, cm.model.createData(), s.q)
        M = np.triu(M) + np.triu(M, 1).T
        b = s.tau - pin.nonLinearEffects(cm.model, cm.model.createData(), s.q, s.v)
        a0, N = null_space.svd_null_space(J, gamma)
        svd = a0 + N @ np.linalg.solve(N.T @ M @ N, N.T @ (b - M @ a0))
        assert np.abs(a - kkt).max() <= 1e-10 * scale and np.abs(a - svd).max() <= 1e-10 * scale
        assert np.abs(J @ a + gamma).max() <= 1e-10 * (np.abs(J).max() * scale + np.abs(gamma).max())
        exact = core.forward_dynamics(cm, cd, s.q, s.v, s.tau, "nullspace")
        np.testing.assert_array_equal(exact.a, a)
        np.testing.assert_allclose(exact.constraint_force, M @ a - b, rtol=0, atol=1e-9 * np.abs(b).max())


def test_a_state_with_no_rigid_answer_is_handed_over_and_refused(load_cached):
    """On the truss, a velocity along the freedom that exists only instantaneously: gamma leaves the range
    of J, the fast solve hands the state over (its range test, the bounded path's), and the exact method
    refuses it."""
    m = load_cached("deployable_9rr12uru")
    cm, cd = m.closure_model, m.closure_model.create_data()
    s = make_samples(m, 1)[0]
    assert _solve(cm, cd, s.q, s.v, s.tau)[2] is not None  # the partition at a regular, consistent state
    q, v, tau, _ = inconsistent_state(m)
    assert _solve(cm, cd, q, v, tau)[2] is None
    with pytest.raises(InconsistentMotion):
        core.forward_dynamics(cm, cd, q, v, tau, "nullspace")


def test_a_change_of_rank_is_handed_to_the_bounded_path():
    """Three rows on four coordinates, the third the sum of the first two where the partition is chosen
    (rank 2): solved there; where the third row becomes independent (rank 3) the rows R's null space is
    not J's (J N != 0) and where the rows R lose a rank the pivots fail: both handed over (None)."""
    rng = np.random.default_rng(5)
    J = rng.standard_normal((3, 4))
    J[2] = J[0] + J[1]
    cd = SimpleNamespace(partition=None, dense_plan=None)
    gamma, M, f = J @ rng.standard_normal(4), np.diag([1.0, 2.0, 3.0, 4.0]), rng.standard_normal(4)
    null_space.partitioned_null_space(cd, J, gamma)
    rows = cd.partition[0]
    assert rows.size == 2
    a = dense_forward.solve(cd, J, gamma, 0.0, M, f, TOL)
    np.testing.assert_allclose(J @ a + gamma, 0.0, atol=1e-14)
    lifted = J.copy()
    lifted[2] += 1e-3 * rng.standard_normal(4)  # rank 3: the rows R no longer span
    assert dense_forward.solve(cd, lifted, lifted @ rng.standard_normal(4), 0.0, M, f, TOL) is None
    dropped = J.copy()
    dropped[rows[1]] = 2.0 * dropped[rows[0]]  # the rows R of rank 1
    assert dense_forward.solve(cd, dropped, gamma, 0.0, M, f, TOL) is None


def test_at_the_five_bar_fold_the_answer_is_the_bounded_path_s(load_cached, monkeypatch):
    """At the five-bar's fold (distal links collinear: the passive block singular, the closure rows still
    of full rank), with the partition of a regular state, the exact method's answer with the fast solve is
    the one without it."""
    m = load_cached("five_bar")
    cm, cd = m.closure_model, m.closure_model.create_data()
    prox2 = float(m.home_q[m.q_index("prox2")])
    regular = np.asarray(getattr(q := m.assemble({"prox1": 0.5, "prox2": prox2}), "q", q), dtype=float)
    fold, tau, v = _five_bar_fold(m), np.linspace(1.0, -1.0, cm.nv), np.zeros(cm.nv)
    _solve(cm, cd, regular, v, tau)
    assert _solve(cm, cd, fold, v, tau)[2] is not None
    with_fast = core.forward_dynamics(cm, cd, fold, v, tau, "nullspace").a
    monkeypatch.setattr(dense_forward, "solve", lambda *args: None)
    bounded = core.forward_dynamics(cm, cm.create_data(), fold, v, tau, "nullspace").a
    np.testing.assert_allclose(with_fast, bounded, rtol=0, atol=1e-10 * np.abs(bounded).max())


def test_declines_a_singular_block_and_a_free_motion_without_inertia():
    """Synthetic rows: a partition whose square block is singular gives None (the pivots), as does a mass
    matrix with no inertia along the free motion (N^T M N not positive definite); no partition, None."""
    J = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 1.0]])
    cd = SimpleNamespace(partition=(np.array([0, 1]), np.array([0, 1]), np.array([2])), dense_plan=None)
    gamma, f = np.array([0.5, -1.0]), np.array([1.0, 2.0, 3.0])
    a = dense_forward.solve(cd, J, gamma, 0.0, np.eye(3), f, TOL)
    np.testing.assert_allclose(J @ a + gamma, 0.0, atol=1e-15)
    np.testing.assert_allclose(a, [-0.5, 0.0, 1.0], atol=1e-15)  # a = f + J^T lambda, lambda = (-1.5, -2)
    singular = np.array([[1.0, 0.0, 0.0], [2.0, 0.0, 1.0]])
    assert dense_forward.solve(cd, singular, gamma, 0.0, np.eye(3), f, TOL) is None
    assert dense_forward.solve(cd, J, gamma, 0.0, np.diag([1.0, 0.0, 0.0]), f, TOL) is None
    assert (
        dense_forward.solve(SimpleNamespace(partition=None, dense_plan=None), J, gamma, 0.0, np.eye(3), f, TOL) is None
    )


@pytest.mark.parametrize("name", ["five_bar", "deployable_9rr12uru"])
def test_off_the_manifold_with_baumgarte_the_outcome_is_the_bounded_path_s(name, load_cached, monkeypatch):
    """An integrator's stage off the manifold (every coordinate moved 1e-12, 1e-10, 1e-6 or 1e-3 from a bench
    state, the velocity kept), with and without Baumgarte terms, the partition kept from the bench state: the
    exact method gives with the fast solve what it gives without it, the accelerations to 1e-12 relative or
    the same refusal (the fast answer kept near the manifold, handed over where the truss's redundant row's
    drift is not cancelled)."""
    m = load_cached(name)
    cm, s = m.closure_model, make_samples(m, 1)[0]
    fast_solve, kept = dense_forward.solve, []

    def counted(*args):
        a = fast_solve(*args)
        kept.append(a is not None)
        return a

    for off in (1e-12, 1e-10, 1e-6, 1e-3):
        for gains in (None, (100.0, 20.0)):
            out = []
            for solve in (counted, lambda *args: None):
                monkeypatch.setattr(dense_forward, "solve", solve)
                cd = cm.create_data()
                core.forward_dynamics(cm, cd, s.q, s.v, s.tau, "nullspace")  # the partition at the bench state
                try:
                    out.append(core.forward_dynamics(cm, cd, s.q + off, s.v, s.tau, "nullspace", baumgarte=gains).a)
                except MechkitError as error:
                    out.append(type(error))
            if isinstance(out[1], type):
                assert out[0] is out[1]
            else:
                np.testing.assert_allclose(out[0], out[1], rtol=0, atol=1e-12 * np.abs(out[1]).max())
    assert any(kept)
