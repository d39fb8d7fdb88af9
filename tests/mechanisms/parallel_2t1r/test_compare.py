"""`mechkit.mechanisms.parallel_2t1r.compare`: SOC and classic virtual work against Pinocchio along the
motion law, plain and redundantly actuated; which reaction components are determinate."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.parallel_2t1r.compare import compare_along

REGULAR = np.arange(1, 501) * 0.01  # the 501-sample law without its singular start t = 0


@pytest.fixture(scope="module")
def comparison(mech):
    return compare_along(mech, REGULAR)


def test_soc_and_classic_agree_with_pinocchio_along_the_motion_law(comparison):
    """The 500 regular samples: torques and determinate reactions within 1e-8 of the largest value."""
    assert comparison.kinematics_error.max() < 1e-10
    assert np.all(comparison.relative_error("soc") < 1e-8)
    assert np.all(comparison.relative_error("classic")[:3] < 1e-8)
    assert np.all(np.abs(comparison.values["pinocchio"]).max(axis=0)[[0, 1, 3, 4, 5, 6]] > 0.5)  # not trivial


def test_in_plane_forces_are_the_determinate_components(comparison):
    """All axes parallel: fx, fz (and my of a free pin) are fixed by statics; fy, mx, mz are not."""
    for joint in ("R23", "R43"):
        np.testing.assert_array_equal(comparison.determinate[joint], [True, False, True, False, True, False])


def test_redundant_minimum_norm_distribution_agrees_everywhere(mech):
    cmp = compare_along(mech, REGULAR[::25], redundant=True)
    assert np.all(cmp.relative_error("soc") < 1e-8)
    assert np.all(cmp.relative_error("classic")[:3] < 1e-8)
