"""The Lagrange first-kind validator on linkages with hand solutions (pendulum, motor, four-bar)."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.validation.lagrange import Body, Linkage, Pin, Spring

G = 9.81


def pendulum(motors=(), springs=()) -> Linkage:
    """A 0.8 m rod (2 kg) pinned to the wall at the origin, its frame's x axis along the rod."""
    rod = Body("rod", 2.0, 2.0 * 0.8**2 / 12, np.array([0.4, 0.0]))
    return Linkage([rod], [Pin("A", None, np.zeros(2), 0, np.zeros(2))], motors, springs)


def pendulum_state(phi: float, rate: float) -> tuple[np.ndarray, np.ndarray]:
    c, s = np.cos(phi), np.sin(phi)
    return np.array([0.4 * c, 0.4 * s, phi]), np.array([-0.4 * s * rate, 0.4 * c * rate, rate])


def four_bar() -> Linkage:
    """Crank 0.1, coupler 0.28, rocker 0.22, ground 0.3 (a Grashof crank-rocker), rods of 1 kg/m."""

    def rod(name, length):
        return Body(name, length, length**3 / 12, np.array([length / 2, 0.0]))

    bodies = [rod("crank", 0.1), rod("coupler", 0.28), rod("rocker", 0.22)]
    pins = [
        Pin("A", None, np.zeros(2), 0, np.zeros(2)),
        Pin("B", 0, np.array([0.1, 0.0]), 1, np.zeros(2)),
        Pin("D", None, np.array([0.3, 0.0]), 2, np.zeros(2)),
        Pin("C", 1, np.array([0.28, 0.0]), 2, np.array([0.22, 0.0])),
    ]
    return Linkage(bodies, pins)


def four_bar_state(L: Linkage, crank: float) -> np.ndarray:
    """Closed four-bar coordinates at a crank angle (circle intersection, C above the ground line)."""
    B = 0.1 * np.array([np.cos(crank), np.sin(crank)])
    D = np.array([0.3, 0.0])
    d = np.linalg.norm(D - B)
    u = (D - B) / d
    along = (0.28**2 - 0.22**2 + d**2) / (2 * d)
    C = B + along * u + np.sqrt(0.28**2 - along**2) * np.array([-u[1], u[0]])
    q = np.empty(9)
    for i, (start, end) in enumerate([(np.zeros(2), B), (B, C), (D, C)]):
        phi = np.arctan2(*(end - start)[::-1])
        q[3 * i : 3 * i + 3] = [*(start + (end - start) / 2), phi]
    assert np.max(np.abs(L.constraints(q))) < 1e-14
    return q


@pytest.mark.parametrize("phi, rate", [(0.3, 0.0), (-1.1, 2.5), (2.0, -4.0)])
def test_pendulum_matches_the_hand_solution(phi, rate):
    L = pendulum()
    q, qd = pendulum_state(phi, rate)
    sol = L.solve(q, qd)
    inertia_pivot = 2.0 * 0.8**2 / 3
    assert sol.qdd[2] == pytest.approx(-2.0 * G * 0.4 * np.cos(phi) / inertia_pivot, rel=1e-12)
    # pin force on the rod = m (a_com - g)
    assert np.allclose(sol.forces["A"], 2.0 * (sol.qdd[:2] - L.gravity), rtol=1e-12, atol=1e-12)
    centripetal = -0.4 * rate**2 * np.array([np.cos(phi), np.sin(phi)])
    tangential = 0.4 * sol.qdd[2] * np.array([-np.sin(phi), np.cos(phi)])
    assert np.allclose(sol.qdd[:2], centripetal + tangential, rtol=1e-12, atol=1e-12)


def test_prescribed_motor_torque_is_the_inverse_dynamics():
    L = pendulum(motors=("A",))
    q, qd = pendulum_state(0.7, 1.5)
    sol = L.solve(q, qd, [3.0])
    assert sol.qdd[2] == pytest.approx(3.0, rel=1e-14)
    expected = 2.0 * 0.8**2 / 3 * 3.0 + 2.0 * G * 0.4 * np.cos(0.7)
    assert sol.efforts["A"] == pytest.approx(expected, rel=1e-12)


def test_spring_damper_torque_enters_like_a_motor():
    k, free, c = 5.0, 0.2, 0.4
    L = pendulum(springs=(Spring("A", k, free, c),))
    q, qd = pendulum_state(0.7, 1.5)
    torque = k * (free - 0.7) - c * 1.5
    inertia_pivot = 2.0 * 0.8**2 / 3
    assert L.solve(q, qd).qdd[2] == pytest.approx((torque - 2.0 * G * 0.4 * np.cos(0.7)) / inertia_pivot, rel=1e-12)
    assert L.power(q, qd, {})["damper"] == pytest.approx(c * 1.5**2)
    assert L.energy(q, qd)["spring"] == pytest.approx(0.5 * k * (0.7 - free) ** 2)


def test_jacobian_and_gamma_are_the_derivatives_of_the_constraints():
    L = four_bar()
    q = four_bar_state(L, 0.8)
    rng = np.random.default_rng(1)
    qd = rng.normal(size=9)
    eps = 1e-6
    numeric = np.column_stack(
        [(L.constraints(q + eps * e) - L.constraints(q - eps * e)) / (2 * eps) for e in np.eye(9)]
    )
    assert np.max(np.abs(numeric - L.jacobian(q))) < 1e-9
    # gamma = -(d C_q / dt) qd
    dJ = (L.jacobian(q + eps * qd) - L.jacobian(q - eps * qd)) / (2 * eps)
    assert np.max(np.abs(L.gamma(q, qd) + dJ @ qd)) < 1e-8


def test_free_four_bar_conserves_energy_and_stays_closed():
    L = four_bar()
    q = four_bar_state(L, 0.8)
    Cq = L.jacobian(q)
    qd = np.linalg.svd(Cq)[2][-1] * 3.0  # the one motion the pins allow
    e0 = sum(L.energy(q, qd).values())
    dt = 1e-3
    for _ in range(300):
        k1 = L.solve(q, qd).qdd
        k2 = L.solve(q + dt / 2 * qd, qd + dt / 2 * k1).qdd
        k3 = L.solve(q + dt / 2 * (qd + dt / 2 * k1), qd + dt / 2 * k2).qdd
        k4 = L.solve(q + dt * (qd + dt / 2 * k2), qd + dt * k3).qdd
        q, qd = q + dt * qd + dt**2 / 6 * (k1 + k2 + k3), qd + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        q, qd = L.project(q, qd)
    assert np.max(np.abs(L.constraints(q))) < 1e-13
    assert abs(sum(L.energy(q, qd).values()) - e0) < 1e-8 * max(1.0, abs(e0))


def test_projection_returns_to_the_manifold():
    L = four_bar()
    q = four_bar_state(L, 2.0) + 1e-3 * np.random.default_rng(2).normal(size=9)
    q, qd = L.project(q, np.ones(9))
    assert np.max(np.abs(L.constraints(q))) < 1e-13
    assert np.max(np.abs(L.jacobian(q) @ qd)) < 1e-12


def test_bad_inputs_raise_named_errors():
    with pytest.raises(InvalidParameters, match="pin"):
        pendulum(motors=("nope",))
    with pytest.raises(InvalidParameters, match="bodies"):
        Linkage([Body("b", 0.0, 1.0, np.zeros(2))], [Pin("A", None, np.zeros(2), 0, np.zeros(2))])
    L = pendulum(motors=("A", "A"))  # the same angle prescribed twice: A is singular
    with pytest.raises(SingularConfiguration):
        L.solve(*pendulum_state(0.1, 0.0), [0.0, 0.0])
