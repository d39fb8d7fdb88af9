"""The 2T1R as a mechanism: mobility and the redundantly actuated variant; its declared motion law is
the paper's."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.parallel_2t1r.motion_law import motion_law


def test_mobility_and_redundant_variant(load_cached):
    plain, redundant = load_cached("parallel_2t1r"), load_cached("parallel_2t1r", redundant_actuation=True)
    assert plain.mobility().dof == 3 and plain.mobility().redundant == 0
    assert plain.actuated == ("R11", "R21", "R31") and redundant.actuated == ("R11", "R21", "R31", "R41")
    np.testing.assert_allclose(redundant.home_q, plain.home_q, atol=1e-12)


def test_declared_motion_law_is_the_papers(mech):
    """`SPEC.motion_laws["motion_law"]` samples the paper's law exactly (values, rates, accelerations),
    without its singular start, as `motion.from_callable` does."""
    from mechkit import motion
    from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_DURATION

    law = motion.from_law(mech, "motion_law", 7)
    ref = motion.from_callable(mech, motion_law, np.linspace(MOTION_DURATION / 7, MOTION_DURATION, 7))
    assert law.names == ("R11", "R21", "R31") == ref.names
    for field in ("t", "values", "rates", "accelerations"):
        assert np.array_equal(getattr(law, field), getattr(ref, field)), field
    assert len(motion.from_law(mech, "motion_law").t) == 501
    with pytest.raises(InvalidParameters, match="declares the motion laws: motion_law"):
        motion.from_law(mech, "nothing")
