"""`mechkit.base.json_text`: JSON as RFC 8259 has it (no Infinity, no NaN), numpy values converted, a
non-finite number refused with its path, and `nulls` giving None with the reason beside it."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from mechkit.base.exceptions import OutputError
from mechkit.base.json_text import dumps, nulls


def _strict(text: str):
    def refuse(constant):
        raise ValueError(constant)

    return json.loads(text, parse_constant=refuse)


def test_numpy_values_become_plain_json():
    text = dumps({"a": np.float64(1.5), "b": np.arange(3), "c": (np.bool_(True), None, "x"), 4: np.int32(2)})
    assert _strict(text) == {"a": 1.5, "b": [0, 1, 2], "c": [True, None, "x"], "4": 2}


@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan, np.float64("nan")])
def test_a_non_finite_number_is_refused_with_its_path(bad):
    with pytest.raises(OutputError, match=r"\$\.rows\[1\]\.k.*must be null"):
        dumps({"rows": [{"k": 1.0}, {"k": bad}]})


def test_nulls_say_why():
    values, why = nulls({"x": 2.0, "y": math.inf, "z": math.nan}, "held rigidly")
    assert values == {"x": 2.0, "y": None, "z": None} and why == {"y": "held rigidly", "z": "held rigidly"}
    assert _strict(dumps({"held": values, "held_why": why}))["held"]["y"] is None
