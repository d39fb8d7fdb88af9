"""The fast paths of the inverse dynamics give what the exact per-sample computations give.

Regularity judged on the gathered closure Jacobian (vs `kinematics.check_regular`), row residuals
from joint placements (vs `ClosureRows.residual`), QR solutions of full-rank [S, J^T] (vs the SVD
minimum-norm solution) and self-stress spaces from cached rows (vs the SVD null space, and the
determinacy flags computed on it), on random configurations of every registered mechanism.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from test_bad_inputs_singular import DISTANCES, _singular_inputs

from mechkit.base.exceptions import SingularConfiguration
from mechkit.bench.sampling import make_samples
from mechkit.catalog import registry
from mechkit.core import inverse, kinematics


def _arrays(m, samples):
    p = m._id_problem
    Q, V, A = (np.array([getattr(s, k) for s in samples]) for k in "qva")
    oMi, J, b, _ = inverse._gather(p, Q, V, A, [None] * len(Q))
    return p, oMi, J, b


def _exact_determinacy(p, oMi, J, points):
    """The determinacy flags on the SVD null space of every sample, one sample at a time."""
    na, out, eff = p.actuated_v.size, [], []
    for i in range(len(oMi)):
        Wf = p.full.wrenches(oMi[i:i + 1])
        A = inverse._system(p, p.full.jacobian(Wf, J[i:i + 1]))
        _, s, Vt = np.linalg.svd(A[0])
        null = Vt[int(np.sum(s > kinematics.RANK_TOL * s[0])):].T[None]
        loads = inverse._cut_loads(p, p.full, Wf, null[:, na:].transpose(0, 2, 1), points[i:i + 1])
        variation = np.sqrt(np.square(loads).sum(axis=1))[0]
        effort_variation = np.sqrt(np.square(null[0, :na]).sum(axis=1))
        tol = inverse.DETERMINACY_TOL * max(variation.max(initial=0.0), effort_variation.max(initial=0.0), 1e-300)
        out.append(variation <= tol)
        eff.append(effort_variation <= tol)
    return np.array(out), np.array(eff)


def _points(p, oMi):
    return np.concatenate([oMi[:, 1:, :3, 3], p.kept.evaluate(oMi)[2]], axis=1)


@pytest.mark.parametrize("name", registry.names())
def test_self_stresses_span_the_svd_null_space_and_give_the_exact_flags(name, load_cached):
    m = load_cached(name)
    p, oMi, J, _ = _arrays(m, make_samples(m, 6, seed=11))
    A = inverse._system(p, p.full.jacobian(p.full.wrenches(oMi), J))
    null = inverse._self_stresses(p, A)
    for i in range(len(A)):
        _, s, Vt = np.linalg.svd(A[i])
        exact = Vt[int(np.sum(s > kinematics.RANK_TOL * s[0])):].T
        basis = null[i][:, np.linalg.norm(null[i], axis=0) > 0]
        assert basis.shape == exact.shape
        np.testing.assert_allclose(basis.T @ basis, np.eye(basis.shape[1]), atol=1e-12)
        np.testing.assert_allclose(basis @ basis.T, exact @ exact.T, atol=1e-10)
    points = _points(p, oMi)
    flags, efforts = inverse._determinacy(p, oMi, J, points)
    want, want_efforts = _exact_determinacy(p, oMi, J, points)
    np.testing.assert_array_equal(flags, want)
    np.testing.assert_array_equal(efforts, want_efforts)


@pytest.mark.parametrize("name", ["four_bar", "parallel_2t1r", "ten_bar", "deployable_9rr12uru"])
def test_self_stresses_fall_back_to_the_svd_where_the_cached_rows_do_not_certify(name, load_cached):
    m = load_cached(name)
    p, oMi, J, _ = _arrays(m, make_samples(m, 4, seed=5))
    A = inverse._system(p, p.full.jacobian(p.full.wrenches(oMi), J))
    want = inverse._svd_null_spaces(A)
    cached = p.stress_rows
    try:
        p.stress_rows = cached[:-1] if cached is not None and cached.size else np.arange(1)  # too few rows
        got = inverse._self_stresses(p, A)
    finally:
        p.stress_rows = cached
    for g, w in zip(got, want):
        np.testing.assert_allclose(g @ g.T, w @ w.T, atol=1e-10)


@pytest.mark.parametrize("name", registry.names())
def test_row_residuals_and_cut_points_from_placements(name, load_cached):
    """Off the closure (random q), the gathered residual norms and p_b equal `ClosureRows`' own."""
    m = load_cached(name)
    model, data = m.model, m.model.createData()
    rng_state = np.random.get_state()
    np.random.seed(3)
    try:
        qs = [pin.randomConfiguration(model, -np.ones(model.nq), np.ones(model.nq)) for _ in range(3)]
    finally:
        np.random.set_state(rng_state)
    for q in qs:
        kinematics.update_kinematics(model, data, q)
        oMi = np.array([M.np for M in data.oMi.tolist()])[None]
        for rows, rw in ((m.rows, m._id_problem.kept), (m.full_rows, m._id_problem.full)):
            _, residual, points = rw.evaluate(oMi)
            want = np.linalg.norm(rows.residual(data))
            assert abs(residual[0] - want) <= 1e-13 * max(1.0, want)
            for c, cut in enumerate(rows.cuts):
                np.testing.assert_allclose(points[0, c], data.oMf[cut.frame_b].translation, atol=1e-14)


@pytest.mark.parametrize("name", ["ten_bar", "deployable_9rr12uru"])
def test_full_rank_qr_solution_is_the_svd_minimum_norm_solution(name, load_cached):
    m = load_cached(name)
    p, oMi, J, b = _arrays(m, make_samples(m, 4, seed=2))
    A = inverse._system(p, p.kept.jacobian(p.kept.wrenches(oMi), J))
    assert A.shape[1] != A.shape[2]
    x, outside = inverse._full_rank_solution(A, b)
    for i in range(len(A)):
        want = np.linalg.lstsq(A[i], b[i], rcond=None)[0]
        assert np.max(np.abs(x[i] - want)) <= 1e-10 * max(1.0, np.max(np.abs(want)))
        assert outside[i] <= 1e-9 * max(1.0, np.linalg.norm(b[i]))


def test_regularity_is_judged_as_check_regular_at_the_collinear_five_bar(load_cached):
    """Near the five-bar's singular inputs, inverse_dynamics raises exactly where check_regular does,
    one sample or batched; with allow_singular it returns."""
    m = load_cached("five_bar")
    free_v = m._split(list(m.actuated))[1]
    z = np.zeros(m.model.nv)
    regular = m.home_q
    for root, side in _singular_inputs(m):
        for d in DISTANCES:
            q = m.assemble({"prox1": 2.6, "prox2": root + side * d}, guess=m.home_q)
            try:
                kinematics.check_regular(m.rows, m.model.createData(), q, free_v, m.independent_rows)
                singular = False
            except SingularConfiguration:
                singular = True
            zeros = np.zeros((2, m.model.nv))
            for state in ((q, z, z), (np.array([regular, q]), zeros, zeros)):
                if singular:
                    with pytest.raises(SingularConfiguration):
                        m.inverse_dynamics(*state)
                else:
                    m.inverse_dynamics(*state)
            m.inverse_dynamics(q, z, z, allow_singular=True, determinacy=False)


@pytest.mark.parametrize("name", ["four_bar", "ten_bar", "deployable_9rr12uru"])
@pytest.mark.parametrize("determinacy", [True, False])
def test_zero_samples_give_empty_results(name, determinacy, load_cached):
    """A motion study may hand over no sample: every path keeps the (0, ...) shapes."""
    m = load_cached(name)
    p, nv = m._id_problem, m.model.nv
    for distribution in inverse.DISTRIBUTIONS:
        out = inverse.inverse_dynamics_batch(p, np.zeros((0, m.model.nq)), np.zeros((0, nv)), np.zeros((0, nv)), [],
                                             determinacy, distribution, m.independent_rows)
        assert out.efforts.shape == (0, len(m.actuated)) and out.reactions.shape == (0, len(p.joint_names), 6)
        assert (out.determinate is None) != determinacy


@pytest.mark.parametrize("name", registry.names())
def test_gather_reads_each_sample_fresh_from_pinocchio(name, load_cached):
    """The gather's held views of data give, per sample, what a fresh data's Pinocchio calls give."""
    m = load_cached(name)
    model, p = m.model, m._id_problem
    samples = make_samples(m, 3)
    Q, V, A = (np.array([getattr(s, k) for s in samples]) for k in "qva")
    oMi, J, tau, _ = inverse._gather(p, Q, V, A, [None] * len(Q))
    for i in range(len(Q)):
        data = model.createData()
        pin.computeJointJacobians(model, data, Q[i])
        np.testing.assert_array_equal(oMi[i], np.array([M.np for M in data.oMi.tolist()]))
        np.testing.assert_array_equal(J[i], data.J)
        np.testing.assert_array_equal(tau[i], pin.rnea(model, data, Q[i], V[i], A[i]))
