"""Motion studies the tests share, computed once per module: the 2T1R along its paper's law, the four-bar
along a crank swing."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit import motion
from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_DURATION, motion_law

from .laws import crank_law


@pytest.fixture(scope="module")
def two_t1r(load_cached):
    mech = load_cached("parallel_2t1r")
    law = motion.from_callable(mech, motion_law, np.linspace(0.2, MOTION_DURATION, 12))
    return mech, motion.study(mech, law, determinacy=True)


@pytest.fixture(scope="module")
def four_bar(load_cached):
    mech = load_cached("four_bar")
    return mech, motion.study(mech, motion.from_callable(mech, crank_law, np.linspace(0.0, 3.0, 16)))
