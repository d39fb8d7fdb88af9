"""Physical identities of every registered mechanism (one test per mechanism, so one failure hides none)."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import support_balance_error

from mechkit.catalog.registry import specs
from mechkit.report import report

NAMES = list(specs())


@pytest.mark.parametrize("name", NAMES)
def test_report_self_checks(name, load_cached):
    r = report(load_cached(name))
    assert r["checks"]["closure_residual"] < 1e-10
    for key in ("velocity_constraint", "acceleration_constraint"):
        if key in r["checks"]:
            assert r["checks"][key] < 1e-9, key
    if "kkt_vs_proximal" in r["checks"]:
        assert r["checks"]["kkt_vs_proximal"] < 1e-8
    assert r["checks"]["inverse_forward_roundtrip"] < 1e-8


@pytest.mark.parametrize("name", NAMES)
def test_supports_carry_weight_and_inertia(name, load_cached):
    """Newton's second law of the whole mechanism from the support reactions of the constrained RNEA."""
    m = load_cached(name)
    q = m.home_q
    v = np.zeros(m.model.nv)
    a = m.forward_dynamics(q, v, np.zeros(m.model.nv), "kkt").a  # free motion from rest under gravity
    assert support_balance_error(m, q, v, a) < 1e-9
