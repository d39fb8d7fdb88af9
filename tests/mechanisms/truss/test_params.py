"""`mechkit.mechanisms.truss.params`: impossible geometry refused."""

from __future__ import annotations

import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.tetra_3rr3uru import TetraParams


@pytest.mark.parametrize("bad", [{"l2": 0.6}, {"alpha_ref": 2.0}, {"L": 2.0}])
def test_params_refuse_impossible_geometry(bad):
    with pytest.raises(InvalidParameters):
        TetraParams(**bad)
