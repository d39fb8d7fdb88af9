"""`mechkit.validation.soc`: sequential SOC virtual work against hand-derived answers."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.validation.planar_motion import AXIS
from mechkit.validation.soc import BodyLoad, SKCInstant, WrenchSite, classic_virtual_work, solve_soc

G = np.array([0.0, 0.0, -9.81])


def _pendulum(theta: float, rate: float, acc: float, free_pivot: bool) -> tuple[SKCInstant, float, float]:
    """A bar of length L pinned at the origin, actuated at the pin, in the x-z plane.

    With ``free_pivot`` the virtual coordinates are (x_A, z_A, theta) and the pin's in-plane force
    is released; otherwise the single coordinate is theta. Returns the SKC, m and I_com (about y).
    """
    length, mass = 0.4, 1.3
    i_com = mass * length**2 / 12.0
    e = np.array([np.cos(theta), 0.0, np.sin(theta)])  # along the bar
    n_perp = np.array([-np.sin(theta), 0.0, np.cos(theta)])  # d e / d theta
    a_com = 0.5 * length * (acc * n_perp - rate**2 * e)
    inertia = np.diag([0.0, i_com, 0.0]) + np.diag([1.0, 0.0, 1.0]) * 1e-3  # y entry is the planar one
    if free_pivot:
        jv = np.column_stack([[1.0, 0, 0], [0, 0, 1.0], 0.5 * length * n_perp])
        jw = np.column_stack([np.zeros(3), np.zeros(3), AXIS])
        pin = np.vstack([jv - np.outer(0.5 * length * n_perp, [0, 0, 1.0]), jw])
        released = (WrenchSite("pin", pin, +1.0, (0, 2)),)
        actuator = np.array([0.0, 0.0, 1.0])
    else:
        jv, jw = (0.5 * length * n_perp)[:, None], AXIS[:, None]
        released, actuator = (), np.array([1.0])
    body = BodyLoad("bar", mass, inertia, a_com, rate * AXIS, acc * AXIS, jv, jw)
    skc = SKCInstant("pendulum", jv.shape[1], (body,), (("pin", actuator),), released)
    return skc, mass, i_com


@pytest.mark.parametrize("free_pivot", [False, True])
@pytest.mark.parametrize("theta", [-0.7, 0.0, 0.4, 2.5])
def test_pendulum_torque_by_hand(theta: float, free_pivot: bool) -> None:
    rate, acc, length = 1.7, -3.2, 0.4
    skc, mass, i_com = _pendulum(theta, rate, acc, free_pivot)
    i_pivot = i_com + mass * (0.5 * length) ** 2
    expected = mass * 9.81 * 0.5 * length * np.cos(theta) + i_pivot * acc
    result = solve_soc([skc], G)
    assert result.efforts["pin"] == pytest.approx(expected, rel=1e-12, abs=1e-12)
    assert classic_virtual_work(_pendulum(theta, rate, acc, False)[0], G)["pin"] == pytest.approx(expected, rel=1e-12)
    if free_pivot:
        e = np.array([np.cos(theta), 0.0, np.sin(theta)])
        n_perp = np.array([-np.sin(theta), 0.0, np.cos(theta)])
        a_com = 0.5 * length * (acc * n_perp - rate**2 * e)
        force = mass * (a_com - G)  # ground on bar: Newton's law
        np.testing.assert_allclose(result.reactions["pin"][[0, 2]], force[[0, 2]], rtol=1e-12, atol=1e-12)
        assert np.all(result.reactions["pin"][[1, 3, 4, 5]] == 0.0)


def test_spinning_body_needs_newton_euler_wrench() -> None:
    """A 3D body held at its COM by one 6-component joint: reaction = (m (a - g), I alpha + w x I w)."""
    rng = np.random.default_rng(7)
    half = rng.normal(size=(3, 3))
    inertia = half @ half.T + np.eye(3)  # non-diagonal: the gyroscopic term is nonzero
    mass, acc, omega, alpha = 2.5, rng.normal(size=3), rng.normal(size=3), rng.normal(size=3)
    eye = np.eye(6)
    body = BodyLoad("body", mass, inertia, acc, omega, alpha, eye[:3], eye[3:])
    skc = SKCInstant("free body", 6, (body,), released=(WrenchSite("holder", eye, +1.0),))
    expected = np.concatenate([mass * (acc - G), inertia @ alpha + np.cross(omega, inertia @ omega)])
    np.testing.assert_allclose(solve_soc([skc], G).reactions["holder"], expected, rtol=1e-13, atol=1e-13)


def test_released_basis_equals_components() -> None:
    """Unknowns along a rotated in-plane basis (along / across the bar) give the same reaction."""
    theta = 0.8
    skc, _, _ = _pendulum(theta, 1.1, 0.4, True)
    along = [np.cos(theta), 0.0, np.sin(theta), 0.0, 0.0, 0.0]
    across = [-np.sin(theta), 0.0, np.cos(theta), 0.0, 0.0, 0.0]
    site = WrenchSite("pin", skc.released[0].jacobian, 1.0, basis=np.column_stack([along, across]))
    rotated = SKCInstant(skc.name, skc.n, skc.bodies, skc.actuators, (site,))
    np.testing.assert_allclose(
        solve_soc([rotated], G).reactions["pin"], solve_soc([skc], G).reactions["pin"], rtol=1e-13, atol=1e-13
    )


def test_rank_deficient_raises() -> None:
    skc, _, _ = _pendulum(0.3, 0.0, 0.0, True)
    parallel = (("u1", np.array([0, 0, 1.0])), ("u2", np.array([0, 0, 2.0])))  # same direction twice
    twice = SKCInstant(skc.name, skc.n, skc.bodies, parallel)
    with pytest.raises(SingularConfiguration, match="pendulum"):
        solve_soc([twice], G)


def test_known_joint_must_be_released_first() -> None:
    skc, _, _ = _pendulum(0.3, 0.0, 0.0, True)
    orphan = SKCInstant("orphan", skc.n, skc.bodies, skc.actuators, known=skc.released)
    with pytest.raises(InvalidParameters, match="pin"):
        solve_soc([orphan], G)
