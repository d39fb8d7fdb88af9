"""The rank judge (`mechkit.core.rank`): numerical rank, independent rows, the resolvable singular value,
the passive verdict and its error, the part of a right-hand side outside a range."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import SingularConfiguration
from mechkit.core import rank


def test_rank_is_relative_to_the_largest_singular_value():
    assert rank.numerical_rank(np.array([1e6, 1.0, 1e-2, 1e-4])) == 3  # 1e-4 < 1e-9 x 1e6 < 1e-2
    assert rank.numerical_rank(np.array([1e-20, 1e-25])) == 2  # relative: a tiny scale is still full rank
    assert rank.numerical_rank(np.zeros(3)) == 0 and rank.numerical_rank(np.zeros(0)) == 0
    np.testing.assert_array_equal(rank.ranks(np.array([[3.0, 2.0, 0.0], [1.0, 1e-12, 0.0]])), [2, 1])


def test_independent_rows_span_the_row_space():
    rng = np.random.default_rng(0)
    A = rng.normal(size=(3, 6))
    J = np.vstack([A, A[0] + 2 * A[2], A[1]])  # rows 3 and 4 repeat the first three
    rows = rank.independent_rows(J)
    assert len(rows) == 3 and np.linalg.matrix_rank(J[rows]) == 3


def test_resolvable_singular_value_is_sqrt_of_residual_times_scale():
    assert rank.resolvable_singular_value(4.0, 1e-12) == pytest.approx(rank.SINGULAR_MARGIN * 2e-6)
    # floored at rounding: a residual below eps s_max resolves no better than eps s_max
    assert rank.resolvable_singular_value(1.0, 0.0) == pytest.approx(rank.SINGULAR_MARGIN * np.sqrt(rank.EPS))


def test_passive_verdict_and_its_error():
    s = np.array([[2.0, 1.0], [2.0, 1e-7], [2.0, 0.0]])  # 1e-7: above rank 1, below what 1e-12 resolves
    cond, bad = rank.passive_verdict(s, 2, np.full(3, 1e-12))
    np.testing.assert_array_equal(bad, [False, True, True])
    assert cond[0] == 2.0 and np.isinf(cond[2])
    with pytest.raises(SingularConfiguration, match="smallest singular value"):
        rank.check_passive(s[:2], 2, 1e-12)
    with pytest.raises(SingularConfiguration, match="determines only 1 of the 2"):
        raise rank.singular_error(s[2], 2, 1e-12)
    with pytest.raises(SingularConfiguration, match="give more inputs"):
        raise rank.singular_error(np.array([1.0]), 2, 1e-12)


def test_outside_range_and_inconsistency():
    rng = np.random.default_rng(1)
    J = rng.normal(size=(4, 3))
    inside = J @ rng.normal(size=3)
    U, _, _ = np.linalg.svd(J)
    normal = U[:, 3]  # the left null vector
    for b, want in ((inside, 0.0), (inside + 0.5 * normal, 0.5)):
        got = rank.outside_range(U[None], np.array([3]), b[None])[0]
        assert got == pytest.approx(want, abs=1e-12)
    assert rank.inconsistency(J, -inside) < 1e-12
    assert rank.inconsistency(J, -(inside + 0.5 * normal)) == pytest.approx(0.5 * np.abs(normal).max(), rel=1e-9)


@pytest.mark.parametrize("shape", [(3, 3), (5, 3), (3, 5)])
def test_regularity_bounds_bracket_the_singular_values_and_certify_only_what_they_pass(shape):
    """1 / |X|_F <= sigma_min(m, k) and |B|_F >= sigma_max, one block (LAPACK) as N (numpy); a certified
    block passes `passive_verdict`; a nearly singular one is not certified, an exactly singular one has rho
    near 0."""
    rng = np.random.default_rng(3)
    B = rng.normal(size=(6, *shape))
    lines = B if shape[0] >= shape[1] else B.transpose(0, 2, 1)  # the columns of a tall block, the rows of a wide one
    lines[4, :, 0] = lines[4, :, 1] * (1 + 1e-13)  # nearly singular
    lines[5, :, 0] = lines[5, :, 1]  # singular
    rho, size = rank.regularity_bounds(B)
    s = np.linalg.svd(B, compute_uv=False)
    assert np.all(rho <= s[:, -1] * (1 + 1e-12) + 1e-12 * size) and np.all(size >= s[:, 0])  # to rounding
    for i in range(len(B)):
        one = rank.block_bounds(B[i])
        assert one == pytest.approx((rho[i], size[i]), rel=1e-9, abs=1e-300)
    residual = np.full(len(B), 1e-12)
    certified = rank.certified_regular(rho, size, residual)
    _, bad = rank.passive_verdict(s, min(shape), residual)
    assert certified[:4].all() and not certified[4:].any() and not np.any(certified & bad)
    assert rank.block_bounds(B[5])[0] <= 1e-3 * rho[0] and rank.certified_regular(*rank.block_bounds(B[0]), 1e-12)


def test_a_block_whose_inverse_cannot_be_squared_counts_as_singular_without_raising():
    """A block with a singular value of 1e-300 (an MJCF anchor of -1e-300 made one): its inverse's entries square to
    overflow; under the callers' np.errstate(over="raise") the bounds once raised FloatingPointError. Now rho is 0
    (the batch's squares overflow) or the block's own 1e-300 (one block's scaled BLAS norm), either way not regular."""
    B = np.array([[1.0, 0.0], [0.0, 1e-300]])
    tall = np.array([[1.0, 0.0], [0.0, 1e-300], [0.0, 0.0]])
    with np.errstate(all="raise"):
        for block in (B, tall):
            rho, size = rank.regularity_bounds(block[None])
            assert rho[0] == 0.0 and size[0] == pytest.approx(1.0)
            rho, size = rank.block_bounds(block)
            assert rho <= 1e-300 * (1 + 1e-12) and size == pytest.approx(1.0)
            assert not rank.certified_regular(rho, size, 1e-12)


def test_an_empty_block_gives_no_bound_and_no_lapack_complaint(capfd):
    """A passive block with no column (a field robot's SDF arm at home) has no R to invert: no bound (rho 0,
    the SVD decides, as before), and nothing printed by LAPACK (it printed an illegal-value error)."""
    assert rank.triangular_inverse(np.zeros((3, 0)), 0) is None
    assert rank.block_bounds(np.zeros((3, 0)))[0] == 0.0
    printed = capfd.readouterr()
    assert "illegal value" not in printed.out + printed.err
