"""The platform held level along a ship's roll and pitch: every sample level, and the carrier's wrench
from the study is Newton's law for the whole carried system, M (a_G - g)."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit.bases import CARRIER_JOINT, base_motion, with_base
from mechkit.bases.held_motion import held_motion

UP = ((0.0, 0.0, 1.0), (0.0, 0.0, 1.0))


def _ship(t):
    """Roll 10 deg over 8 s, pitch 4 deg over 6 s, heave 0.2 m over 7 s (ours)."""
    amp, w = np.array([0, 0, 0.2, np.radians(10), np.radians(4), 0]), 2 * np.pi / np.array([1, 1, 7, 8, 6, 1])
    return amp * np.sin(w * t), amp * w * np.cos(w * t), -amp * w * w * np.sin(w * t)


@pytest.fixture(scope="module")
def held(load_cached):
    mech = with_base(load_cached("spherical_2dof"), "moving")
    return mech, held_motion(mech, base_motion.from_callable(_ship, np.linspace(0, 4, 21)), "platform", UP)


def test_every_sample_level(held):
    mech, out = held
    assert out.tilt.max() < 1e-10 and out.names == ("r11", "r21")
    data, fid = mech.model.createData(), mech.model.getFrameId("platform")
    for q in out.study.q:
        pin.framesForwardKinematics(mech.model, data, q)
        assert np.linalg.norm(data.oMf[fid].rotation[:2, 2]) < 1e-9


def test_carrier_wrench_is_newton_for_the_carried_system(held):
    mech, out = held
    r = out.study
    k = list(r.joints).index(CARRIER_JOINT)
    data, mass = mech.model.createData(), pin.computeTotalMass(mech.model)
    for q, v, a, reaction in zip(r.q, r.v, r.a, r.reactions[:, k]):
        pin.centerOfMass(mech.model, data, q, v, a)
        np.testing.assert_allclose(reaction[:3], mass * (data.acom[0] - mech.model.gravity.linear), atol=1e-9)
