"""`mechkit.mechanisms.ten_bar.studies`: the deployment's cross-checks."""

from __future__ import annotations

import pytest


@pytest.mark.slow
def test_cross_checks_short(mech):
    """The deployment's cross-checks over 0.2 s."""
    from mechkit.mechanisms.ten_bar.studies import cross_check_lines, cross_checks

    c = cross_checks(mech, t_end=0.2, samples=3)
    assert "worst relative difference" in "\n".join(cross_check_lines(c))
    assert c.reaction_disagreement < 1e-12
