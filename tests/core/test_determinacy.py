"""Determinacy (`mechkit.core.determinacy`): the self-stress spaces from cached rows are the SVD null
spaces, and the flags computed on them are the exact ones, on every registered mechanism."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.bench.sampling import make_samples
from mechkit.catalog import registry
from mechkit.core import determinacy as det
from mechkit.core import inverse, inverse_plan
from mechkit.core.rank import RANK_TOL


def _arrays(m, samples):
    """Placements of the used joints, data.J, q and the joints' points of the samples (the inverse pass)."""
    cm, cd = m.closure_model, m.closure_model.create_data()
    Q, V, A = (np.array([getattr(s, k) for s in samples]) for k in "qva")
    P, J, _, _ = inverse.inverse_pass(cm, cd, Q, V, A, [None] * len(Q))
    G = inverse_plan.used_placements(cm, P)
    return cm, cd, G, J, Q, P[:, 1:, :, 3], cm.kernel.cut_points(G)


def _system(cm, G, J, Q):
    full = cm.full_kernel
    return det.system(cm, full.jacobian(full.row_wrenches(G), J, Q))


def _exact_flags(cm, G, J, Q, origins, points):
    """The determinacy flags on the SVD null space of every sample, one sample at a time."""
    na, out, eff = len(cm.actuated), [], []
    full = cm.full_kernel
    for i in range(len(G)):
        Wf = full.row_wrenches(G[i : i + 1])
        A = det.system(cm, full.jacobian(Wf, J[i : i + 1], Q[i : i + 1]))
        _, s, Vt = np.linalg.svd(A[0])
        null = Vt[int(np.sum(s > RANK_TOL * s[0])) :].T[None]
        loads = full.joint_loads(
            Wf[:, None], null[:, na:].transpose(0, 2, 1), origins[i : i + 1, None], points[i : i + 1, None]
        )
        variation = np.sqrt(np.square(loads).sum(axis=1))[0]
        effort_variation = np.sqrt(np.square(null[0, :na]).sum(axis=1))
        tol = det.DETERMINACY_TOL * max(variation.max(initial=0.0), effort_variation.max(initial=0.0), 1e-300)
        out.append(variation <= tol)
        eff.append(effort_variation <= tol)
    return np.array(out), np.array(eff)


@pytest.mark.parametrize("name", registry.names())
def test_self_stresses_span_the_svd_null_space_and_give_the_exact_flags(name, load_cached):
    m = load_cached(name)
    cm, cd, G, J, Q, origins, points = _arrays(m, make_samples(m, 6, seed=11))
    A = _system(cm, G, J, Q)
    null = det.self_stresses(cd, A)
    for i in range(len(A)):
        _, s, Vt = np.linalg.svd(A[i])
        exact = Vt[int(np.sum(s > RANK_TOL * s[0])) :].T
        basis = null[i][:, np.linalg.norm(null[i], axis=0) > 0]
        assert basis.shape == exact.shape
        np.testing.assert_allclose(basis.T @ basis, np.eye(basis.shape[1]), atol=1e-12)
        np.testing.assert_allclose(basis @ basis.T, exact @ exact.T, atol=1e-10)
    flags, efforts = det.determinacy(cm, cd, G, J, Q, origins, points)
    want, want_efforts = _exact_flags(cm, G, J, Q, origins, points)
    np.testing.assert_array_equal(flags, want)
    np.testing.assert_array_equal(efforts, want_efforts)


@pytest.mark.parametrize("name", ["four_bar", "parallel_2t1r", "ten_bar", "deployable_9rr12uru"])
def test_self_stresses_fall_back_to_the_svd_where_the_cached_rows_do_not_certify(name, load_cached):
    m = load_cached(name)
    cm, cd, G, J, Q, _, _ = _arrays(m, make_samples(m, 4, seed=5))
    A = _system(cm, G, J, Q)
    want = det.svd_null_spaces(A)
    det.self_stresses(cd, A)  # caches the rows
    cd.stress_rows = cd.stress_rows[:-1] if cd.stress_rows.size else np.arange(1)  # too few rows
    cd.stress_columns = None  # the QR path on the rows (the LU one: the rank-change test below)
    got = det.self_stresses(cd, A)
    for g, w in zip(got, want):
        np.testing.assert_allclose(g @ g.T, w @ w.T, atol=1e-10)


def _one_sample_flags(m, cd, q, planned=False):
    """`determinacy_one` at q, after Pinocchio's pass: the fast path (cached columns) where it certifies; from
    the gathered placements, or (`planned`) from the world vectors of the inverse dynamics' plan."""
    import pinocchio as pin

    cm = m.closure_model
    pin.computeJointJacobians(cm.model, cd.pin, q)
    G = cd.used_placements()
    if not planned:
        return det.determinacy_one(cm, cd, cd.J, q, cd.oMi[1:, :, 3], cm.kernel.cut_points(G))
    p = inverse_plan.plan(cm, cd)
    p.fill_world()
    return det.determinacy_one(cm, cd, cd.J, q, p.origins, cm.kernel.points(p.rows_world), world=p.full_world)


@pytest.mark.parametrize("name", registry.names())
def test_one_sample_flags_are_the_exact_ones(name, load_cached):
    """The one-sample determinacy (the solve's null space where the cuts keep their spatial rows, else the
    cached columns' LU) gives the flags of the SVD null space, sample by sample."""
    m = load_cached(name)
    samples = make_samples(m, 6, seed=3)
    cm, _, G, J, Q, origins, points = _arrays(m, samples)
    want, want_efforts = _exact_flags(cm, G, J, Q, origins, points)
    for i, s in enumerate(samples):
        r = m.inverse_dynamics(s.q, s.v, s.a)
        np.testing.assert_array_equal(r.determinate, want[i])
        np.testing.assert_array_equal(r.efforts_determinate_values, want_efforts[i])
        cd = m.closure_model.create_data()
        flags, efforts = _one_sample_flags(m, cd, samples[0].q)  # caches the columns at the first sample
        flags, efforts = _one_sample_flags(m, cd, s.q)
        np.testing.assert_array_equal(flags, want[i])
        np.testing.assert_array_equal(efforts, want_efforts[i])


def _five_bar_fold(m):
    """The five-bar where its distal links are collinear (the limit of prox1 with prox2 at home): the roots
    of the two closure rows and det of the passive block (dist1, dist2), by Newton from an assembly near
    it. There [S^T, J^T] loses a rank: one more self-stress."""
    import pinocchio as pin
    import scipy.optimize

    cm = m.closure_model
    cd = cm.create_data()
    q = m.assemble({"prox1": 2.0, "prox2": float(m.home_q[m.q_index("prox2")])})
    q = np.asarray(getattr(q, "q", q), dtype=float).copy()
    idx = [m.q_index(j) for j in ("prox1", "dist1", "dist2")]

    def f(x):
        q[idx] = x
        pin.computeJointJacobians(cm.model, cd.pin, q)
        e, Jr, _ = cm.kernel.evaluate(cd.used_placements(), cd.J, q)
        return [*e, np.linalg.det(Jr[:, cm.passive_v])]

    x = scipy.optimize.fsolve(f, q[idx], xtol=1e-12)
    assert np.abs(f(x)).max() < 1e-15  # the fold to rounding: the rank drop is beyond RANK_TOL
    return q


@pytest.mark.parametrize("planned", [False, True])
def test_a_change_of_rank_along_a_motion_is_caught_by_the_fast_determinacy(load_cached, planned):
    """Along prox1 of the five-bar up to the fold where its distal links are collinear, the one-sample
    determinacy (columns cached at the first, regular, sample) gives the SVD's flags at every sample: at
    the fold the cached block no longer certifies, the null space grows by one (a self-stress along the
    aligned links) and a component that statics fixed before is no longer fixed. From the gathered
    placements and from the plan's world vectors (`mechkit.core.inverse_plan`, the inverse dynamics' path)."""
    m = load_cached("five_bar")
    cm, cd = m.closure_model, m.closure_model.create_data()
    fold = _five_bar_fold(m)
    prox2 = float(m.home_q[m.q_index("prox2")])
    path = [m.assemble({"prox1": t, "prox2": prox2}) for t in np.linspace(0.5, 1.9, 4)]
    path = [np.asarray(getattr(q, "q", q), dtype=float) for q in path] + [fold]
    dims, found = [], []
    for q in path:
        flags, efforts = _one_sample_flags(m, cd, q, planned)
        G, J = cd.used_placements()[None].copy(), cd.J[None].copy()
        origins, points = cd.oMi[1:, :, 3][None].copy(), cm.kernel.cut_points(G)
        want, want_efforts = _exact_flags(cm, G, J, q[None], origins, points)
        np.testing.assert_array_equal(flags, want[0])
        np.testing.assert_array_equal(efforts, want_efforts[0])
        dims.append(det.svd_null_spaces(_system(cm, G, J, q[None])).shape[2])
        found.append(flags)
    assert dims[:-1] == [dims[0]] * (len(path) - 1) and dims[-1] == dims[0] + 1
    assert (found[-2] & ~found[-1]).any()  # determinate before the fold, not at it
