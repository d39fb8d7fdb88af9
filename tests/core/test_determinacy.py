"""Determinacy (`mechkit.core.determinacy`): the self-stress spaces from cached rows are the SVD null
spaces, and the flags computed on them are the exact ones, on every registered mechanism."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.bench.sampling import make_samples
from mechkit.catalog import registry
from mechkit.core import determinacy as det
from mechkit.core import inverse
from mechkit.core.rank import RANK_TOL


def _arrays(m, samples):
    """Placements of the used joints, data.J, q and the joints' points of the samples (the inverse pass)."""
    cm, cd = m.closure_model, m.closure_model.create_data()
    Q, V, A = (np.array([getattr(s, k) for s in samples]) for k in "qva")
    P, J, _, _ = inverse.inverse_pass(cm, cd, Q, V, A, [None] * len(Q))
    G = inverse.used_placements(cm, P)
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
    got = det.self_stresses(cd, A)
    for g, w in zip(got, want):
        np.testing.assert_allclose(g @ g.T, w @ w.T, atol=1e-10)
