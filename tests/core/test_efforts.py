"""The statics of inverse dynamics (`mechkit.core.efforts`): the QR solutions are the SVD's minimum-norm
solution, the split through the passive block gives it too and certifies only what the singular values
confirm, one sample and N give the same numbers."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.bench.sampling import make_samples
from mechkit.core import efforts, inverse, inverse_plan, rank


def _systems(m, count=4, seed=2):
    """Closure Jacobians (N, rows, nv), [S^T, J^T] (N, nv, na + rows), right-hand sides and residuals of samples."""
    cm = m.closure_model
    samples = make_samples(m, count, seed=seed)
    Q, V, A = (np.array([getattr(s, k) for s in samples]) for k in "qva")
    P, J, b, _ = inverse.inverse_pass(cm, cm.create_data(), Q, V, A, [None] * len(Q))
    b = b if not m.springs else b - m.passive_forces(Q, V)  # the ten-bar's spring
    e, Jrows, _ = cm.kernel.evaluate(inverse_plan.used_placements(cm, P), J, Q)
    return Jrows, inverse.system(cm, Jrows), b, np.linalg.norm(e, axis=-1)


@pytest.mark.parametrize("name", ["ten_bar", "deployable_9rr12uru"])
def test_full_rank_qr_solution_is_the_svd_minimum_norm_solution(name, load_cached):
    _, system, b, _ = _systems(load_cached(name))
    assert system.shape[1] != system.shape[2]
    x, outside, rho = efforts.full_rank_solution(system, b)
    for i in range(len(system)):
        want = np.linalg.lstsq(system[i], b[i], rcond=None)[0]
        assert np.max(np.abs(x[i] - want)) <= 1e-10 * max(1.0, np.max(np.abs(want)))
        assert outside[i] <= 1e-9 * max(1.0, np.linalg.norm(b[i]))
        assert 0 < rho[i] <= np.linalg.svd(system[i], compute_uv=False)[-1]


def test_the_split_gives_the_svd_minimum_norm_solution_and_certifies_what_the_svd_confirms(load_cached):
    """The deployable (a redundant row): through one LU of a square part of the passive block, the
    minimum-norm [u; lambda] of the whole system, one sample as N; the block certified regular where its
    singular values pass."""
    m = load_cached("deployable_9rr12uru")
    cm = m.closure_model
    Jrows, system, b, residuals = _systems(m)
    assert efforts.splits(cm, Jrows.shape[1], "min_norm") and not efforts.splits(cm, Jrows.shape[1], "min_effort")
    x, regular = efforts.passive_solve(cm, cm.create_data(), Jrows, b, residuals)
    assert regular.all()
    for i in range(len(system)):
        want = np.linalg.lstsq(system[i], b[i], rcond=None)[0]
        assert np.max(np.abs(x[i] - want)) <= 1e-10 * max(1.0, np.max(np.abs(want)))
        one, one_regular = efforts.passive_one(cm, cm.create_data(), Jrows[i], b[i], float(residuals[i]))
        np.testing.assert_array_equal(one, x[i])
        assert one_regular
        s = np.linalg.svd(Jrows[i][:, cm.passive_v], compute_uv=False)
        assert not rank.passive_verdict(s[None], s.size, residuals[i : i + 1])[1][0]


def test_a_singular_passive_block_is_not_certified(load_cached):
    """A passive column made dependent on the others: no certificate, no split solution (the caller
    judges by singular values and solves by SVD)."""
    m = load_cached("deployable_9rr12uru")
    cm = m.closure_model
    Jrows, _, b, residuals = _systems(m, count=1)
    J = Jrows[0].copy()
    free = cm.passive_v
    J[:, free[0]] = J[:, free[1]]
    x, regular = efforts.passive_one(cm, cm.create_data(), J, b[0], float(residuals[0]))
    assert x is None and not regular
    assert rank.block_bounds(J[:, free])[0] < rank.RANK_TOL * np.linalg.norm(J[:, free])


@pytest.mark.parametrize("shape", [(9, 8), (7, 3), (6, 9), (3, 7)])
def test_one_sample_full_rank_solution_is_the_batch_one(shape):
    """`full_rank_solution` on one sample (LAPACK directly) gives the batch's least-squares or minimum-norm x,
    the part of b outside the range, and a bound 1 / |R^-1|_F at most the smallest singular value."""
    rng = np.random.default_rng(5)
    A, b = rng.normal(size=(3, *shape)), rng.normal(size=(3, shape[0]))
    x, outside, rho = efforts.full_rank_solution(A, b)
    for i in range(len(A)):
        one = efforts.full_rank_solution(A[i : i + 1], b[i : i + 1])
        np.testing.assert_allclose(one[0][0], x[i], rtol=0, atol=1e-13 * np.abs(x[i]).max())
        np.testing.assert_allclose(one[0][0], np.linalg.lstsq(A[i], b[i], rcond=None)[0], atol=1e-12)
        assert one[1][0] == pytest.approx(outside[i], abs=1e-13) and one[2][0] == pytest.approx(rho[i], rel=1e-12)
        assert one[2][0] <= np.linalg.svd(A[i], compute_uv=False)[-1] * (1 + 1e-12)


def test_square_bounds_bound_the_smallest_singular_value_and_refuse_a_singular_system():
    """`square_bounds`: 1 / |A^-1|_F <= sigma_min(A) for regular systems, 0 for an exactly singular one."""
    rng = np.random.default_rng(6)
    A = rng.normal(size=(4, 5, 5))
    rho = efforts.square_bounds(A)
    assert np.all(rho > 0) and np.all(rho <= np.linalg.svd(A, compute_uv=False)[:, -1] * (1 + 1e-12))
    A[2, :, 0] = A[2, :, 1]
    assert np.all(efforts.square_bounds(A) == 0.0)  # one singular system: no bound for any (the SVD judges)
