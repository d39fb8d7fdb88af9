"""`mechkit.mechanisms.spherical_2dof.params`: the paper's values; bad parameters named."""

from __future__ import annotations

import math

import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.spherical_2dof import Spherical2DofParams

P = Spherical2DofParams()


def test_defaults_are_the_papers_values():
    deg = {k: math.degrees(getattr(P, k)) for k in ("alpha1", "alpha2", "beta", "eta11", "eta12", "eta21", "eta22")}
    assert deg == pytest.approx(
        {"alpha1": 25, "alpha2": 30, "beta": 53.13, "eta11": 0, "eta12": 90, "eta21": 0, "eta22": 90},
        abs=1e-12,
    )


@pytest.mark.parametrize(
    "change, name",
    [
        ({"beta_platform": P.beta}, "beta_platform"),
        ({"beta_platform": math.radians(150)}, "beta_platform"),
        ({"alpha1": 0.0}, "alpha1"),
        ({"rows": "planar"}, "rows"),
    ],
)
def test_bad_parameters_are_named(change, name):
    with pytest.raises(InvalidParameters) as err:
        P.replace(**change)
    assert err.value.name == name
