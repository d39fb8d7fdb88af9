"""The failure atlas: every method fails with a growing error or a clear exception, never a silent NaN."""

from __future__ import annotations

import numpy as np

from mechkit.base import exceptions
from mechkit.bench import failure_atlas

KNOWN = {"ok", "other branch", "root lost"} | {n for n in dir(exceptions) if n[0].isupper()}


def _check(cases):
    assert cases
    for c in cases:
        assert c.outcome in KNOWN, c
        assert np.isfinite(c.error) == (c.outcome in ("ok", "other branch")), c


def test_singularity_error_grows_then_assembly_refuses():
    cases = failure_atlas.singularity(quick=True)
    _check(cases)
    cond = [c for c in cases if c.method == "passive-block condition number" and c.condition > 0]
    assert cond[-1].error > 1e5 * cond[0].error  # the passive block degenerates as the gap closes
    kkt = {c.condition: c.error for c in cases if c.method == "forward dynamics, dense KKT" and c.condition > 0}
    assert kkt[1e-2] < 1e-12 and kkt[min(kkt)] > 1e-11  # accuracy lost, not silently: a finite growing error
    past = [c for c in cases if c.condition < 0]
    assert {c.outcome for c in past} == {"InvalidParameters", "ClosureNotConverged"}


def test_proximal_mu_zero_raises_and_kkt_is_exact():
    cases = failure_atlas.proximal_mu(quick=True)
    _check(cases)
    for c in cases:
        if c.method.startswith("constraintDynamics") and c.condition == 0.0:
            assert c.outcome == "SingularConfiguration"
        if c.method.startswith("dense KKT") or (c.method.endswith("it=20") and 0 < c.condition <= 1e-3):
            assert c.error < 1e-10, c
    biased = [c for c in cases if c.method.endswith("it=1") and c.condition == 1e-1]
    assert biased and all(c.outcome == "ConstraintViolated" for c in biased)  # far off: refused, never returned


def test_far_starts_land_somewhere_or_say_so():
    cases = failure_atlas.far_starts(quick=True)
    _check(cases)
    for method in {c.method for c in cases}:
        assert any(c.method == method and c.outcome == "ok" for c in cases)


def test_unstabilised_integration_drifts_more():
    cases = failure_atlas.integration(quick=True)
    _check(cases)
    end = {}
    for c in cases:
        end[c.method] = c.error
    assert end["semi-implicit Euler, no stabilisation"] > 3 * end["semi-implicit Euler, Baumgarte"]
    assert end["RK4, no stabilisation"] < 1e-6 < end["semi-implicit Euler, no stabilisation"]


def test_root_loss_cases_are_finite_or_named():
    _check(failure_atlas.root_loss(quick=True))
