"""`mechkit.mechanisms.four_bar.params`: a bad parameter is named."""

from __future__ import annotations

import pytest

import mechkit
from mechkit.base.exceptions import InvalidParameters


@pytest.mark.parametrize(
    "params, name",
    [
        ({"crank": -0.1}, "crank"),
        ({"coupler": 0.0}, "coupler"),
        ({"ground": float("nan")}, "ground"),
        ({"gears": 3}, "gears"),
        ({"ground": 2.0}, "ground/crank/coupler/rocker"),
    ],
)
def test_bad_parameters_name_the_parameter(params, name):
    with pytest.raises(InvalidParameters) as err:
        mechkit.load("four_bar", **params)
    assert err.value.name == name
