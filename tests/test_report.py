"""`mechkit.report`: the self-checks of every registered mechanism."""

from __future__ import annotations

import pytest

from mechkit.catalog.registry import specs
from mechkit.report import report


@pytest.mark.parametrize("name", list(specs()))
def test_report_self_checks(name, load_cached):
    r = report(load_cached(name))
    assert r["checks"]["closure_residual"] < 1e-10
    for key in ("velocity_constraint", "acceleration_constraint"):
        if key in r["checks"]:
            assert r["checks"][key] < 1e-9, key
    if "kkt_vs_proximal" in r["checks"]:
        assert r["checks"]["kkt_vs_proximal"] < 1e-8
    assert r["checks"]["inverse_forward_roundtrip"] < 1e-8
