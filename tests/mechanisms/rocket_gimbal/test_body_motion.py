"""`mechkit.mechanisms.rocket_gimbal.body_motion`: the analytic motion against finite differences of
the geometry."""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.rocket_gimbal.body_motion import gimbal_motion
from mechkit.mechanisms.rocket_gimbal.kinematics import (
    actuator_lengths,
)
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene

from .paper_example import GEO


def test_analytic_motion_matches_finite_differences_of_the_geometry():
    scene, t, h = SwingScene(), 0.37, 1e-5
    motions = [gimbal_motion(GEO, *scene.angles(t + k * h)) for k in (-1, 0, 1)]
    for i in range(2):
        legs = [m.legs[i] for m in motions]
        rate_fd = (legs[2].length - legs[0].length) / (2 * h)
        acc_fd = (legs[2].length - 2 * legs[1].length + legs[0].length) / h**2
        assert np.isclose(legs[1].length_rate, rate_fd, rtol=1e-7, atol=1e-9)
        assert np.isclose(legs[1].length_acc, acc_fd, rtol=1e-4, atol=1e-5)
        hooke_fd = (legs[2].hooke - legs[0].hooke) / (2 * h)
        hooke_acc_fd = (legs[2].hooke - 2 * legs[1].hooke + legs[0].hooke) / h**2
        assert np.allclose(legs[1].hooke_rate, hooke_fd, rtol=1e-7, atol=1e-9)
        assert np.allclose(legs[1].hooke_acc, hooke_acc_fd, rtol=1e-4, atol=1e-5)
        # the length and the Hooke angles are those of the closed-form IK
        assert np.isclose(legs[1].length, actuator_lengths(GEO, *motions[1].angles)[i], rtol=1e-15)
    # engine angular acceleration: d(omega)/dt by finite differences
    alpha_fd = (motions[2].omega - motions[0].omega) / (2 * h)
    assert np.allclose(motions[1].alpha, alpha_fd, rtol=1e-6, atol=1e-8)
