"""`mechkit.settling`: where the motions no actuator drives settle under gravity and the springs (the
ten-bar: R1 and R3 driven, its passive freedom on the torsion spring at R5; the four-bar unactuated)."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit.settling import (
    SETTLE_TOL,
    SETTLED,
    held_joints,
    outside_range,
    potential_energy,
    rest_load,
    settle,
    undriven_motions,
)


def _closed_step(m, q, held, step):
    """q moved by `step` (nv,) and closed again with the held joints kept."""
    return m.solve_closure(pin.integrate(m.model, q, step), held).q


def test_rest_load_is_the_gradient_of_the_potential_energy(load_cached):
    """Gravity minus the spring's torque against central differences of gravity's and the spring's energy."""
    m = load_cached("ten_bar")
    q, h = m.home_q, 1e-6
    load = rest_load(m, q)
    fd = np.array(
        [
            (
                potential_energy(m, pin.integrate(m.model, q, h * e))
                - potential_energy(m, pin.integrate(m.model, q, -h * e))
            )
            / (2 * h)
            for e in np.eye(m.model.nv)
        ]
    )
    assert np.max(np.abs(fd - load)) < 1e-6 * max(1.0, np.max(np.abs(load)))


def test_the_undriven_motions_close_the_loops_and_keep_the_held_joints(load_cached):
    m = load_cached("ten_bar")
    held = held_joints(m)
    assert held == tuple(m.actuated)
    U = undriven_motions(m, m.home_q, held)
    assert U.shape == (m.model.nv, m.mobility().dof - len(held))
    assert np.allclose(U.T @ U, np.eye(U.shape[1]), atol=1e-12)
    assert np.max(np.abs(m.closure_jacobian(m.home_q) @ U)) < 1e-10
    assert np.max(np.abs(U[[m.v_index(j) for j in held]])) < 1e-12


@pytest.mark.parametrize("name, actuated", [("ten_bar", None), ("four_bar", ())])
def test_settle_finds_a_minimum_of_the_energy_along_the_undriven_motions(load_cached, name, actuated):
    """The settled configuration closes the loops, keeps the held joints, carries no load along the
    undriven motions, and a closed step either way along them raises the energy."""
    m = load_cached(name) if actuated is None else load_cached(name, actuated=actuated)
    held = held_joints(m)
    q = settle(m, m.home_q)
    assert np.max(np.abs(m.closure_residual(q))) < 1e-10
    for joint in held:
        assert np.allclose(m.joint_values(q)[joint], m.joint_values(m.home_q)[joint], atol=1e-12)
    U = undriven_motions(m, q, held)
    load = rest_load(m, q)
    assert np.max(np.abs(U.T @ load)) <= SETTLE_TOL * max(1.0, np.max(np.abs(load)))
    energy = potential_energy(m, q)
    assert energy < potential_energy(m, m.home_q)
    for u in U.T:
        for sign in (1.0, -1.0):
            assert potential_energy(m, _closed_step(m, q, held, sign * 1e-3 * u)) > energy
    assert settle(m, q) is q


def test_outside_range_names_a_joint_that_moved_beyond_its_limits(load_cached):
    m = load_cached("ten_bar")
    start = m.home_q
    i = m.q_index("R5")
    high = m.model.upperPositionLimit[i]
    beyond, inside = start.copy(), start.copy()
    beyond[i], inside[i] = high + 10 * SETTLED, high - 10 * SETTLED
    assert outside_range(m, beyond, start).startswith("R5 at ")
    assert outside_range(m, inside, start) == ""
    assert outside_range(m, beyond, beyond) == ""
