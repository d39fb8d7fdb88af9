"""Property-based bad input (hypothesis) on `mechkit.catalog.params`: per mechanism, parameters drawn
inside and outside their ranges give either a named `MechkitError` or a mechanism whose core
self-checks are finite and below `report.CHECK_LIMIT`; never another exception, never NaN. 100 cases
per mechanism in the default run, 2,000 with `-m slow` (the spec's own checks are added there)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mechkit
from mechkit.base.exceptions import MechkitError
from mechkit.catalog.registry import get_spec, names
from mechkit.loading import from_params
from mechkit.report import CHECK_LIMIT, failing_checks, self_checks


def _numeric_fields(name: str) -> list[tuple[str, float]]:
    params = get_spec(name).params()
    return [
        (f.name, float(getattr(params, f.name)))
        for f in dataclasses.fields(params)
        if isinstance(getattr(params, f.name), (int, float)) and not isinstance(getattr(params, f.name), bool)
    ]


def _value(default: float):
    """Around the default (inside its range) or far from it, negative, zero, nan or inf (outside)."""
    scale = default if default != 0 else 1.0
    return st.one_of(
        st.floats(0.8, 1.25).map(lambda k: default * k if default else k - 1.0),
        st.floats(-3, 3).map(lambda e: scale * 10.0**e),
        st.sampled_from([0.0, -scale, math.nan, math.inf, -math.inf]),
    )


@st.composite
def overrides(draw, name: str):
    fields = _numeric_fields(name)
    chosen = draw(st.lists(st.sampled_from(fields), min_size=1, max_size=min(3, len(fields)), unique=True))
    out = {}
    for field, default in chosen:
        value = draw(_value(default))
        out[field] = (
            int(value) if isinstance(getattr(get_spec(name).params(), field), int) and math.isfinite(value) else value
        )
    return out


def check(name: str, params: dict, spec_checks: bool) -> str:
    """'refused' (a named error) or 'checked' (finite self-checks below the limit); anything else fails."""
    try:
        m = mechkit.load(name, **params)
        if not spec_checks:
            m = from_params(dataclasses.replace(m.spec, self_checks=None), m.params)
        checks, refused = self_checks(m)
    except MechkitError:
        return "refused"
    if refused:  # a check the core refused by name (e.g. a near-singular pose): also a named refusal
        assert all(refused.values()), refused
        return "refused"
    assert all(np.isfinite(v) for v in checks.values()), checks
    assert not failing_checks(checks), (params, failing_checks(checks), CHECK_LIMIT)
    return "checked"


def _test(name: str, examples: int, spec_checks: bool):
    @settings(
        max_examples=examples, deadline=None, derandomize=True, database=None, suppress_health_check=list(HealthCheck)
    )
    @given(overrides(name))
    def run(params):
        check(name, params, spec_checks)

    return run


@pytest.mark.parametrize("name", names())
def test_parameters_give_a_checked_mechanism_or_a_named_error(name):
    _test(name, 100, spec_checks=False)()


@pytest.mark.slow
@pytest.mark.parametrize("name", names())
def test_parameters_long_campaign(name):
    _test(name, 2000, spec_checks=True)()
