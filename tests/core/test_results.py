"""Result types (`mechkit.core.results`): the single-sample result builds its dicts on demand, from the
same arrays a batch result holds."""

from __future__ import annotations

import numpy as np

from mechkit import core


def test_single_result_builds_its_dicts_from_its_arrays():
    names, actuated = ("a", "b", "cut"), ("a",)
    reactions = np.arange(18, dtype=float).reshape(3, 6)
    det = np.ones((3, 6), dtype=bool)
    det[2, 4] = False
    batch = core.BatchInverseDynamicsResult(
        names,
        actuated,
        np.array([[1.5]]),
        reactions[None],
        np.array([True, False, True]),
        np.array([[0.1, 0.2]]),
        np.array([3.0]),
        det[None],
        np.array([[True]]),
    )
    one = batch.sample(0)
    assert len(batch) == 1 and one.condition == 3.0
    assert one.efforts == {"a": 1.5} and one.efforts_determinate == {"a": True}
    assert list(one.reactions) == list(names)
    np.testing.assert_array_equal(one.reactions["cut"].wrench, reactions[2])
    assert one.reactions["cut"].determinate[4] == np.False_ and one.reactions["b"].support is False
    assert one.reactions is one.reactions  # built once
    untested = core.InverseDynamicsResult(
        names, actuated, np.array([1.5]), reactions, np.ones(3, bool), np.zeros(2), 1.0
    )
    assert untested.efforts_determinate is None and untested.reactions["a"].determinate is None


def test_forward_result_computes_the_constraint_force_from_its_rows_on_first_read():
    """Given the rows (J, lambda) instead of J^T lambda, the result computes it on first read, once (later
    changes to the arrays it was given do not reach it), and equals the result given J^T lambda."""
    rng = np.random.default_rng(0)
    J, lam, a = rng.standard_normal((4, 6)), rng.standard_normal(4), rng.standard_normal(6)
    lazy = core.ForwardDynamicsResult(a, None, 3, (J, lam))
    eager = core.ForwardDynamicsResult(a, J.T @ lam, 3)
    first = lazy.constraint_force
    assert np.max(np.abs(first - eager.constraint_force)) <= 1e-15 * np.max(np.abs(first))
    J[:] = 0.0
    assert lazy.constraint_force is first and np.any(first != 0.0)
    assert lazy.iterations == eager.iterations == 3 and lazy.a is a
    assert repr(lazy) == repr(eager).replace(repr(eager.constraint_force), repr(first))
