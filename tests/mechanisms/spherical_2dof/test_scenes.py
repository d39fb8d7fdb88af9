"""`mechkit.mechanisms.spherical_2dof.scenes`: the cone scene's derivatives and cone angle."""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.spherical_2dof.kinematics import platform_normal
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude


def test_cone_scene_derivatives_and_angle():
    t, h = np.linspace(0, 2, 11), 1e-5
    phi, phi_d, phi_dd = cone_attitude(t)
    np.testing.assert_allclose(np.degrees(np.arccos(platform_normal(phi)[:, 2])), 15.0, atol=1e-12)
    fd = (cone_attitude(t + h)[0] - cone_attitude(t - h)[0]) / (2 * h)
    np.testing.assert_allclose(phi_d, fd, atol=1e-8)
    fd2 = (cone_attitude(t + h)[1] - cone_attitude(t - h)[1]) / (2 * h)
    np.testing.assert_allclose(phi_dd, fd2, atol=1e-7)
