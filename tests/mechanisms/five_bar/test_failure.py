"""`mechkit.mechanisms.five_bar.failure`: the five-bar's failure-atlas study."""

from __future__ import annotations

from conftest import assert_failures_named

from mechkit.mechanisms.five_bar.failure import singularity


def test_five_bar_singularity_error_grows_then_assembly_refuses(load_cached):
    """The five-bar's failure-atlas study: driven onto the pose where its
    distal bars are collinear, every method's error grows or it raises by name, never a silent NaN."""
    cases = singularity(load_cached("five_bar"), quick=True)
    assert_failures_named(cases)
    cond = [c for c in cases if c.method == "passive-block condition number" and c.condition > 0]
    assert cond[-1].error > 1e5 * cond[0].error  # the passive block degenerates as the gap closes
    kkt = {c.condition: c.error for c in cases if c.method == "forward dynamics, dense KKT" and c.condition > 0}
    assert kkt[1e-2] < 1e-12 and kkt[min(kkt)] > 1e-11  # accuracy lost, not silently: a finite growing error
    past = [c for c in cases if c.condition < 0]
    assert {c.outcome for c in past} == {"InvalidParameters", "ClosureNotConverged"}
