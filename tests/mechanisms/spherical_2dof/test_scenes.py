"""`mechkit.mechanisms.spherical_2dof.scenes`: the cone scene's derivatives and cone angle."""

from __future__ import annotations

import numpy as np
import pytest

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


def test_held_level_on_the_ship(load_cached):
    """Two seconds of the ship scene: the platform level at every sample, the ship carrying its weight."""
    import pinocchio as pin

    from mechkit.mechanisms.spherical_2dof.scenes import on_ship, ship_motion

    mech = load_cached("spherical_2dof")
    held = on_ship(mech, duration=2.0, samples=11)
    assert held.tilt.max() < 1e-10
    weight = pin.computeTotalMass(mech.model) * 9.81
    heave = ship_motion(held.study.t[-1])[2][2]  # the ship's vertical acceleration at the end
    assert held.study.effort("base_z")[-1] == pytest.approx(weight * (1 + heave / 9.81), rel=2e-2)


def test_the_ship_study_s_lines_say_the_platform_is_level(mech):
    """The ship study's numbers on a short run (2 s, 11 samples): the tilt left is below 1e-10 rad, and the carrier's
    vertical force brackets the platform's weight."""
    from mechkit.mechanisms.spherical_2dof.scenes import on_ship, ship_lines

    lines = ship_lines({"held": on_ship(mech, 2.0, 11)})
    assert float(lines[0].split()[2]) < 1e-10
    low, high = (float(x) for x in lines[-1].split(":")[1].split("N")[0].split(".."))
    weight = sum(i.mass for i in mech.model.inertias) * 9.81
    assert low <= weight * 1.05 and high >= weight * 0.95
