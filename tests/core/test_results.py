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
