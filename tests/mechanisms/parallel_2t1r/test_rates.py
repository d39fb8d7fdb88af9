"""`mechkit.mechanisms.parallel_2t1r.rates`: velocities, accelerations and link motion against finite
differences; the sign of the printed g."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.parallel_2t1r import kinematics as kin
from mechkit.mechanisms.parallel_2t1r import rates
from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_RATES, motion_law, state_at
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams
from mechkit.mechanisms.parallel_2t1r.soc import Points

P = Parallel2T1RParams()


D = P.dims


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
