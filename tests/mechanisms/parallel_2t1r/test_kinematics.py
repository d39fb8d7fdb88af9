"""`mechkit.mechanisms.parallel_2t1r.kinematics`: the paper's example and printed formulas (numpy only)."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.parallel_2t1r import kinematics as kin
from mechkit.mechanisms.parallel_2t1r.branch import EXAMPLE_INPUTS, assembled_pose
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams

P = Parallel2T1RParams()


D = P.dims


def _wrapped(a: np.ndarray) -> np.ndarray:
    return np.angle(np.exp(1j * np.asarray(a)))


def test_example_has_four_poses_each_closing():
    solutions = kin.forward_kinematics(D, EXAMPLE_INPUTS)
    assert sorted(s.branch for s in solutions) == [(0, 0), (0, 1), (1, 0), (1, 1)]
    poses = np.array([s.pose.array() for s in solutions])
    assert np.min(np.linalg.norm(poses[:, None] - poses[None], axis=2) + np.eye(4)) > 1e-3  # distinct
    for s in solutions:
        assert s.discriminant > 1e-3
        assert np.max(np.abs(kin.loop_residuals(D, np.append(EXAMPLE_INPUTS, 0.0), s.pose)[:3])) < 1e-12


def test_c1_matches_paper_eq7_form():
    """Eq. (7): z_p = a x_p + b from the difference of the circles, then m x^2 + n x + k = 0."""
    b1, b2 = kin.elbow_points(D, EXAMPLE_INPUTS[:2])
    a = -(b2[0] - b1[0]) / (b2[2] - b1[2])
    b = (b2 @ b2 - b1 @ b1 - (b2[1] ** 2 - b1[1] ** 2)) / (2 * (b2[2] - b1[2]))
    m, n = 1 + a * a, 2 * (a * b - a * b1[2] - b1[0])
    k = b1[0] ** 2 + (b - b1[2]) ** 2 - D.l2**2
    xs = np.roots([m, n, k])
    paper = sorted((x, a * x + b) for x in xs)
    ours = sorted({(s.pose.x, s.pose.z) for s in kin.forward_kinematics(D, EXAMPLE_INPUTS)})
    np.testing.assert_allclose(paper, ours, atol=1e-14)


def test_follower_satisfies_printed_eq9():
    for s in kin.forward_kinematics(D, EXAMPLE_INPUTS):
        x, z, al = s.pose.x, s.pose.z, s.pose.alpha
        dd = 2 * D.l2 * (D.l3 * np.sin(al) / 2 - z)
        ee = -2 * D.l2 * (D.l1 / 2 - x - D.l3 * np.cos(al) / 2)
        ff = (D.l1 / 2 - x - D.l3 * np.cos(al) / 2) ** 2 + (D.l3 * np.sin(al) / 2 - z) ** 2
        try:
            roots, _ = kin.follower_angles(D, s.pose)
        except InvalidParameters:
            assert ee**2 + dd**2 < ff**2  # limb III cannot reach this pose: no real root of eq. (9)
            continue
        for t4 in roots:
            assert abs(dd * np.sin(t4) + ee * np.cos(t4) + ff) < 1e-14
            assert abs(kin.loop_residuals(D, np.append(EXAMPLE_INPUTS, t4), s.pose)[3]) < 1e-12


def test_inverse_kinematics_eight_sets_round_trip():
    for s in kin.forward_kinematics(D, EXAMPLE_INPUTS):
        sets = kin.inverse_kinematics(D, s.pose)
        assert sets.shape == (8, 3) and len({tuple(np.round(r, 9)) for r in sets}) == 8
        for inputs in sets:
            assert np.max(np.abs(kin.loop_residuals(D, np.append(inputs, 0.0), s.pose)[:3])) < 1e-12
        assert np.min(np.max(np.abs(_wrapped(sets - EXAMPLE_INPUTS)), axis=1)) < 1e-12  # FK -> IK
        for inputs in sets:  # IK -> FK: the pose is among the forward solutions of every set
            poses = [f.pose.array() for f in kin.forward_kinematics(D, inputs)]
            assert min(np.max(np.abs(_wrapped(p - s.pose.array()))) for p in poses) < 1e-10


def test_theta3_matches_printed_eq10_half_angle_form():
    """t3, M3, N3 of eq. (10): N3 u^2 - 2 t3 u - M3 = 0 with u = tan(theta_3 / 2)."""
    pose, _, _ = assembled_pose(D, EXAMPLE_INPUTS)
    x, z, al = pose.x, pose.z, pose.alpha
    xx = -x + D.l3 * np.cos(al) / 2 - D.l1 / 2
    t3 = 2 * D.l2 * z + D.l2 * D.l3 * np.sin(al)
    m3 = 2 * D.l2 * xx - xx**2 - (z + D.l3 * np.sin(al) / 2) ** 2
    n3 = 2 * D.l2 * xx + xx**2 + (z + D.l3 * np.sin(al) / 2) ** 2
    printed = sorted(2 * np.arctan((t3 + sg * np.sqrt(t3**2 + m3 * n3)) / n3) for sg in (1, -1))
    ours = sorted(set(np.round(kin.inverse_kinematics(D, pose)[:, 2], 12)))
    np.testing.assert_allclose(printed, ours, atol=1e-12)


def test_bad_inputs_raise_named_errors():
    with pytest.raises(InvalidParameters, match="theta"):
        kin.forward_kinematics(D, np.array([0.1, np.nan, 0.2]))
    with pytest.raises(InvalidParameters, match="theta"):
        kin.forward_kinematics(D, np.radians([-60.0, 60.0, 0.0]))  # B1B2 > 2 l2: limb I cannot close
    with pytest.raises(InvalidParameters, match="theta1"):
        kin.inverse_kinematics(D, kin.Pose(0.5, 0.3, 0.0))  # out of limb I's reach
    with pytest.raises(InvalidParameters, match="l3"):
        Parallel2T1RParams(l3=2.0)
    with pytest.raises(InvalidParameters, match="l1, l2, l3"):
        Parallel2T1RParams(l1=0.42)  # the example's five-bar no longer closes
