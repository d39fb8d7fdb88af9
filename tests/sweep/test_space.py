"""`mechkit.sweep.space`: axes and design spaces (grid, Latin hypercube, random)."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.sweep import DesignSpace, parse_axis


def test_axes_and_spaces():
    grid = DesignSpace((parse_axis("crank=0.05:0.15:3"), parse_axis("ground=0.25:0.35:2")))
    designs = grid.designs()
    assert designs.shape == (6, 2)
    assert np.allclose(designs[:, 0], [0.05, 0.05, 0.10, 0.10, 0.15, 0.15])
    n = 20
    lhs = DesignSpace((parse_axis("crank=0:1"), parse_axis("ground=2:4")), "lhs", n, seed=3).designs()
    for j, (lo, hi) in enumerate([(0, 1), (2, 4)]):  # one sample in each of the n strata of every axis
        strata = np.floor((lhs[:, j] - lo) / (hi - lo) * n).astype(int)
        assert sorted(strata) == list(range(n))
    rand = DesignSpace((parse_axis("crank=0:1"),), "random", 50, seed=1).designs()
    assert rand.min() >= 0 and rand.max() <= 1
    assert np.array_equal(rand, DesignSpace((parse_axis("crank=0:1"),), "random", 50, seed=1).designs())
    for bad in ("crank", "crank=1:0:3", "crank=a:1:2", "crank=0:1:0"):
        with pytest.raises(InvalidParameters):
            parse_axis(bad)
    with pytest.raises(InvalidParameters):
        DesignSpace((parse_axis("crank=0:1"),)).designs()  # a grid axis needs a count
