"""`mechkit.validation.planar_closed_form`: the closed-form planar four-bar and five-bar close their
loops on both branches, their rates and accelerations are the derivatives, bad input is named."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.validation.planar_closed_form import FiveBarGeometry, FourBarGeometry, five_bar, four_bar
from mechkit.validation.planar_newton_euler import newton_euler

from .planar_laws import TIMES, five_bar_at, four_bar_at


def _e(angle: float) -> np.ndarray:
    return np.array([np.cos(angle), np.sin(angle)])


@pytest.mark.parametrize("elbow_up", [True, False])
@pytest.mark.parametrize("t", TIMES)
def test_four_bar_loop_closes(t: float, elbow_up: bool) -> None:
    g = FourBarGeometry()
    s = four_bar_at(t, elbow_up)
    th1, phi2, th3 = s.q
    loop = g.crank * _e(th1) + g.coupler * _e(th1 + phi2) - g.rocker * _e(th3) - np.array([g.ground, 0.0])
    assert np.max(np.abs(loop)) < 1e-14
    np.testing.assert_allclose(s.links["coupler"].tip, s.links["rocker"].tip, rtol=0, atol=1e-14)
    np.testing.assert_allclose(s.links["crank"].tip, s.links["coupler"].origin, rtol=0, atol=1e-15)


@pytest.mark.parametrize("elbow_up", [True, False])
@pytest.mark.parametrize("t", TIMES)
def test_five_bar_loop_closes(t: float, elbow_up: bool) -> None:
    g = FiveBarGeometry()
    s = five_bar_at(t, elbow_up)
    th1, phi1, th2, phi2 = s.q
    left = g.prox1 * _e(th1) + g.dist1 * _e(th1 + phi1)
    right = np.array([g.ground, 0.0]) + g.prox2 * _e(th2) + g.dist2 * _e(th2 + phi2)
    assert np.max(np.abs(left - right)) < 1e-14


@pytest.mark.parametrize("build", [four_bar_at, five_bar_at])
def test_branch_is_the_larger_z(build) -> None:
    for t in TIMES:
        up, down = build(t, True), build(t, False)
        assert up.joint_position("C")[2] > down.joint_position("C")[2]
        inputs = [up.coordinates.index(j.name) for j in up.joints if j.actuated]
        np.testing.assert_array_equal(up.q[inputs], down.q[inputs])


def _wrapped(d: np.ndarray) -> np.ndarray:
    return (d + np.pi) % (2.0 * np.pi) - np.pi


@pytest.mark.parametrize("build", [four_bar_at, five_bar_at])
@pytest.mark.parametrize("elbow_up", [True, False])
def test_rates_and_accelerations_match_finite_differences(build, elbow_up: bool) -> None:
    """Central differences of positions and angles: first derivative h = 1e-6, second h = 1e-4."""
    for t in TIMES[:-1] + 0.05:
        s = build(t, elbow_up)
        h1, h2 = 1e-6, 1e-4
        lo, hi = build(t - h1, elbow_up), build(t + h1, elbow_up)
        lo2, hi2 = build(t - h2, elbow_up), build(t + h2, elbow_up)
        # FD truncation ~ h^2 * (derivatives ~ 1e2..1e3) and round-off ~ 1e-16 / h^n: both < 1e-6 here
        np.testing.assert_allclose(_wrapped(hi.q - lo.q) / (2 * h1), s.qd, rtol=1e-6, atol=1e-6)
        second = (_wrapped(hi2.q - s.q) - _wrapped(s.q - lo2.q)) / h2**2
        np.testing.assert_allclose(second, s.qdd, rtol=1e-6, atol=1e-5)
        for name, link in s.links.items():
            d_com = (hi.links[name].com - lo.links[name].com) / (2 * h1)
            np.testing.assert_allclose(d_com, link.com_velocity, rtol=1e-6, atol=1e-8)
            dd_com = (hi2.links[name].com - 2 * link.com + lo2.links[name].com) / h2**2
            np.testing.assert_allclose(dd_com, link.com_acceleration, rtol=1e-6, atol=1e-6)
            d_angle = _wrapped(hi.links[name].angle - lo.links[name].angle) / (2 * h1)
            assert d_angle == pytest.approx(link.omega, rel=1e-6, abs=1e-6)
            up, down = hi2.links[name].angle - link.angle, link.angle - lo2.links[name].angle
            assert (_wrapped(up) - _wrapped(down)) / h2**2 == pytest.approx(link.alpha, rel=1e-6, abs=1e-5)


def test_cannot_assemble_names_the_input() -> None:
    with pytest.raises(InvalidParameters, match="theta"):
        four_bar(0.0, geometry=FourBarGeometry(ground=0.30, crank=0.10, coupler=0.10, rocker=0.05))
    with pytest.raises(InvalidParameters, match="thetas"):
        five_bar((np.pi, 0.0))


def test_bad_parameters_and_inputs_raise() -> None:
    with pytest.raises(InvalidParameters, match="crank"):
        FourBarGeometry(crank=-0.1)
    with pytest.raises(InvalidParameters, match="rate"):
        four_bar(0.5, rate=np.nan)
    with pytest.raises(InvalidParameters, match="gravity"):
        newton_euler(four_bar(0.5), np.array([0.0, 1.0, -9.81]))


def test_collinear_coupler_and_rocker_is_singular() -> None:
    # folded pose: B = (0.25, 0), D = (0.5, 0), coupler (0.5) - rocker (0.25) = |BD| exactly
    geometry = FourBarGeometry(ground=0.5, crank=0.25, coupler=0.5, rocker=0.25)
    with pytest.raises(SingularConfiguration, match="collinear"):
        four_bar(0.0, geometry=geometry)
