"""`mechkit.mechanisms.rocket_gimbal.failure`: the gimbal's failure-atlas study."""

from __future__ import annotations


def test_root_loss_cases_are_finite_or_named(mech):
    """The gimbal's failure-atlas study: each root is found with a
    finite error, or its loss is named, never a silent NaN."""
    from conftest import assert_failures_named

    from mechkit.mechanisms.rocket_gimbal.failure import root_loss

    assert_failures_named(root_loss(mech, quick=True))
