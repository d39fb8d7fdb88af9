"""`mechkit.catalog.ranges`: the accepted range of every parameter, bisected from its class's checks."""

from __future__ import annotations

import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.ranges import param_ranges
from mechkit.catalog.registry import get_spec


def test_four_bar_ranges_are_the_loop_closure_inequality():
    """The four-bar class accepts a link up to the sum of the other three: the bisected bounds are those sums."""
    r = param_ranges(get_spec("four_bar").params)
    p = get_spec("four_bar").params()
    lengths = {"ground": p.ground, "crank": p.crank, "coupler": p.coupler, "rocker": p.rocker}
    for name in lengths:
        others = sum(v for k, v in lengths.items() if k != name)
        assert r[name].lower == 0.0 and not r[name].lower_closed
        assert r[name].upper == pytest.approx(others, abs=1e-12) and not r[name].upper_closed
    assert r["density"].text() == "> 0" and r["rows"] is None


def test_closed_and_open_bounds():
    """ten_bar: damping >= 0 (zero accepted); l56 below the wall-gap reach; a free angle has no bound."""
    r = param_ranges(get_spec("ten_bar").params)
    assert r["spring_damping"].text() == ">= 0"
    assert r["stowed_rocker"].text() == "any"
    p = get_spec("ten_bar").params()
    with pytest.raises(InvalidParameters, match="five-bar must close"):
        p.replace(l56=r["l56"].upper * (1 + 1e-4))
    p.replace(l56=r["l56"].upper * (1 - 1e-4))
