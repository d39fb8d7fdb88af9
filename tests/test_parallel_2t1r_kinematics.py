"""The 2T1R's analytic kinematics (numpy only): the paper's example, printed formulas, finite differences."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.mechanisms.parallel_2t1r import kinematics as kin
from mechkit.mechanisms.parallel_2t1r import rates
from mechkit.mechanisms.parallel_2t1r.assembly import EXAMPLE_INPUTS, assembled_pose
from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_RATES, motion_law, state_at
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams
from mechkit.mechanisms.parallel_2t1r.soc import Points

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


def test_sixteen_configurations_of_the_assembled_pose():
    pose, _, _ = assembled_pose(D, EXAMPLE_INPUTS)
    roots, _ = kin.follower_angles(D, pose)
    configs = [np.append(inputs, t4) for inputs in kin.inverse_kinematics(D, pose) for t4 in roots]
    assert len({tuple(np.round(c, 9)) for c in configs}) == 16
    for c in configs:
        assert np.max(np.abs(kin.loop_residuals(D, c, pose))) < 1e-12


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


def _fd(fun, t: float, h: float = 1e-6):
    return (fun(t + h) - fun(t - h)) / (2 * h)


@pytest.mark.parametrize("t", [0.4, 1.7, 3.3, 4.9])
def test_rates_and_accelerations_match_finite_differences(t: float):
    st = lambda u: state_at(P, *motion_law(u))
    s = st(t)
    np.testing.assert_allclose(_fd(lambda u: st(u).pose.array(), t), s.x_dot, atol=1e-8)  # eq. (12)
    np.testing.assert_allclose(_fd(lambda u: st(u).x_dot, t), s.x_ddot, atol=1e-8)  # eq. (15)
    np.testing.assert_allclose(_fd(lambda u: st(u).theta, t), s.theta_dot, atol=1e-8)
    np.testing.assert_allclose(_fd(lambda u: st(u).theta_dot, t), s.theta_ddot, atol=1e-8)


@pytest.mark.parametrize("t", [0.7, 3.9])
def test_link_motion_matches_finite_differences(t: float):
    """Eqs. (16)-(29): COM velocities / accelerations and angular rates against positions."""
    st = lambda u: state_at(P, *motion_law(u))

    def coms(u: float) -> np.ndarray:
        s = st(u)
        pts, motion = Points.of(D, s), rates.link_motion(D, s)
        out = [pts.p]
        for i in range(4):
            for start, name in ((pts.a[i], f"link{i + 1}1"), (pts.b[i], f"link{i + 1}2")):
                out.append(start + 0.5 * D.l2 * kin.direction(motion[name].angle))
        return np.array(out)

    names = ["platform"] + [f"link{i}{e}" for i in range(1, 5) for e in (1, 2)]
    motion = rates.link_motion(D, st(t))
    np.testing.assert_allclose(coms(t), [motion[n].com for n in names], atol=1e-15)
    v = np.array([motion[n].v_com for n in names])
    np.testing.assert_allclose(_fd(coms, t), v, atol=1e-8)
    vel = lambda u: np.array([rates.link_motion(D, st(u))[n].v_com for n in names])
    np.testing.assert_allclose(_fd(vel, t), [motion[n].a_com for n in names], atol=1e-7)
    angle = lambda u: np.unwrap([rates.link_motion(D, st(u))[n].angle for n in names])
    np.testing.assert_allclose(_fd(angle, t), [motion[n].omega[1] for n in names], atol=1e-8)
    omega = lambda u: np.array([rates.link_motion(D, st(u))[n].omega for n in names])
    np.testing.assert_allclose(_fd(omega, t), [motion[n].alpha for n in names], atol=1e-7)


def test_velocity_equation_sign_of_printed_g():
    """J_p v = J_q omega holds with our g_ii; the printed g_ii (opposite sign) would give -v."""
    s = state_at(P, *motion_law(2.0))
    jp, jq = rates.jacobians(D, s.theta, s.pose)
    np.testing.assert_allclose(jp @ s.x_dot, jq @ MOTION_RATES, atol=1e-14)
    r = kin.platform_points(D, s.pose)["C1"] - kin.elbow_points(D, s.theta[:1])[0]
    printed_g11 = 2 * D.l2 * (np.sin(s.theta[0]) * -r[0] + np.cos(s.theta[0]) * -r[2])
    assert np.isclose(printed_g11, -jq[0, 0], rtol=1e-14)


def test_motion_law_start_is_singular_and_flagged():
    theta, rates, acc = motion_law(0.0)
    disc = [s.discriminant for s in kin.forward_kinematics(D, theta)]
    assert max(disc) < kin.DOUBLE_ROOT  # C1 a double root: B1B2 = 2 l2
    with pytest.raises(SingularConfiguration):
        state_at(P, theta, rates, acc)
    assert kin.five_bar_discriminant(D, motion_law(0.01)[0]) > 0.0


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
