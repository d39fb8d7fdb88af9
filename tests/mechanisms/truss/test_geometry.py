"""`mechkit.mechanisms.truss.geometry`: the paper's eq. (6)-(13)."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.spatial import rot_x, rot_y, rot_z
from mechkit.mechanisms.truss.drives import drive_state
from mechkit.mechanisms.truss.geometry import (
    DEG,
    GAMMA0,
    R_B0_ANGLES,
    euler_xyz,
    rot_axis,
    rpy_angles,
)

from .paper import GEOMETRY, TIMES


@pytest.mark.parametrize("t", TIMES)
def test_eq6_web_rods_equal_and_fold_synchronous(t):
    s = drive_state(t)
    p = GEOMETRY.node_positions(s.alpha, s.gamma)
    for node in ("A", "B", "E"):
        assert np.linalg.norm(p["H"] - p[node]) == pytest.approx(0.590, abs=1e-14)
    ab, ae, be = (np.linalg.norm(p[x] - p[y]) for x, y in (("A", "B"), ("A", "E"), ("B", "E")))
    assert ab == pytest.approx(ae, abs=1e-14)
    assert be / ab == pytest.approx(0.250 / 0.2504, rel=1e-13)  # beta makes every link fold alike
    xi = 23.171 * DEG + 0.25 * DEG * t
    assert ab / 2 == pytest.approx(0.2504 * np.cos(xi), rel=5e-4)  # 0.490 = l1 / (L cos beta), printed to 3 digits


@pytest.mark.parametrize("t", TIMES)
def test_eq8_units_are_rotated_copies(t):
    s = drive_state(t)
    p = GEOMETRY.node_positions(s.alpha, s.gamma)
    for a, b in (("B", "C"), ("E", "F"), ("H", "J")):
        np.testing.assert_allclose(p[b], rot_z(-2 * np.pi / 3) @ p[a], atol=1e-15)
    for a, b in (("B", "D"), ("E", "G"), ("H", "I")):
        np.testing.assert_allclose(p[b], rot_z(2 * np.pi / 3) @ p[a], atol=1e-15)


def test_node_velocities_are_the_derivative_of_eq7():
    h = 1e-4
    s, lo, hi = drive_state(120.0), drive_state(120.0 - h), drive_state(120.0 + h)
    v = GEOMETRY.node_velocities(s.alpha, s.gamma, s.alpha_rate, s.gamma_rate)
    p_lo, p_hi = GEOMETRY.node_positions(lo.alpha, lo.gamma), GEOMETRY.node_positions(hi.alpha, hi.gamma)
    for node, vel in v.items():
        np.testing.assert_allclose(vel, (p_hi[node] - p_lo[node]) / (2 * h), atol=1e-11)


def test_eq10_and_eq13_are_consistent_with_eq12():
    k = GEOMETRY.tangent("B")
    R = rot_axis(k, 0.3)
    assert R @ k == pytest.approx(k)
    np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-15)
    gx, gy, gz = 0.4, -0.7, 2.1
    angles = rpy_angles(rot_z(gz) @ rot_y(gy) @ rot_x(gx))
    np.testing.assert_allclose(angles, [gx, gy, gz], atol=1e-14)


def test_eq9_reading_starts_at_the_printed_initial_orientation():
    R = GEOMETRY.node_rotation("B", GAMMA0)
    np.testing.assert_allclose(R, rot_y(GAMMA0) @ euler_xyz(R_B0_ANGLES), atol=1e-15)
