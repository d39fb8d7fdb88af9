"""`mechkit.mechanisms.parallel_2t1r.motion_law`: its start is singular, and flagged."""

from __future__ import annotations

import pytest

from mechkit.base.exceptions import SingularConfiguration
from mechkit.mechanisms.parallel_2t1r import kinematics as kin
from mechkit.mechanisms.parallel_2t1r.motion_law import motion_law, state_at
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams

P = Parallel2T1RParams()


D = P.dims


def test_motion_law_start_is_singular_and_flagged():
    theta, rates, acc = motion_law(0.0)
    disc = [s.discriminant for s in kin.forward_kinematics(D, theta)]
    assert max(disc) < kin.DOUBLE_ROOT  # C1 a double root: B1B2 = 2 l2
    with pytest.raises(SingularConfiguration):
        state_at(P, theta, rates, acc)
    assert kin.five_bar_discriminant(D, motion_law(0.01)[0]) > 0.0
