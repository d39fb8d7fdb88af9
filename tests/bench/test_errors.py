"""`mechkit.bench.errors`: how far a method is from the reference."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.bench import errors


def test_inverse_error_compares_determinate_components_only():
    ref = errors.IDReference(
        {"m1": 2.0},
        {"j": np.array([1.0, 5.0, 0, 0, 0, 0]), "m1": np.array([0, 0, 1.0, 0, -2.0, 0])},
        {"j": np.array([True, False, True, True, True, True]), "m1": np.ones(6, bool)},
    )
    good = {
        "efforts": {"m1": 2.0},
        "reactions": {"j": np.array([1.0, -99.0, 0, 0, 0, 0]), "m1": np.array([0, 0, 1.0, 0, 7.0, 0])},
    }
    err, note = errors.inverse_error(good, ref, ("m1",))
    assert err == 0.0 and note == ""  # the indeterminate fy and the actuated joint's moment are not compared
    bad = {"efforts": {"m1": 2.5}}
    err, note = errors.inverse_error(bad, ref, ("m1",))
    assert err == pytest.approx(0.5 / 5.0) and note == "efforts only"
