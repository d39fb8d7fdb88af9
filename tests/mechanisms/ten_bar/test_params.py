"""`mechkit.mechanisms.ten_bar.params`: bad parameters named; the spring read back from the URDF."""

from __future__ import annotations

import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.ten_bar import params as tp


# ------------------------------------------------------------------ design and description
@pytest.mark.parametrize(
    "change, name",
    [({"l27": 0.1}, "l27/l67"), ({"spring_damping": -1.0}, "spring_damping"), ({"l48": -0.9}, "l48")],
)
def test_bad_parameters_are_named(change, name):
    with pytest.raises(InvalidParameters, match=name):
        tp.TenBarParams(**change)


def test_spring_is_read_from_the_urdf(mech):
    assert tp.spring_from_urdf(mech.urdf) == tp.spring(mech.params)
