"""`mechkit.simulation.friction`: inverse dynamics with joint friction from the reactions, against a hand
computation on the planar four-bar; a friction that locks is refused by name. (Friction in simulation, the
fixed point of `MechanismSystem`: tests/simulation/test_system.py.)"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechkit import forces, simulation
from mechkit.mechanisms.four_bar.closed_form import motion

from .pins import MU, RADIUS, friction

#: Gravity in the x-z plane (m/s^2).
GRAVITY = np.array([0.0, -9.81])


def hand_newton_euler(state, gravity=GRAVITY) -> tuple[float, dict[str, float]]:
    """The crank torque (about -y, ground on crank) and each pin's friction torque T = mu r |F| of the planar
    four-bar by per-link Newton-Euler in the x-z plane, friction moments on both sides of every pin
    (-T tanh(w_rel / threshold) on the child, the opposite on the parent), iterated to the fixed point."""
    links = state.links
    names = list(links)
    row = {n: 3 * i for i, n in enumerate(names)}
    joints = state.joints
    omega = {n: links[n].omega for n in names}
    T = {j.name: 0.0 for j in joints}
    for _ in range(200):
        A = np.zeros((9, 9))
        b = np.zeros(9)
        for k, j in enumerate(joints):
            for side, sign in ((j.parent, -1.0), (j.child, 1.0)):
                if side is None:
                    continue
                r = j.point - links[side].com
                i = row[side]
                A[i : i + 2, 2 * k : 2 * k + 2] += sign * np.eye(2)
                A[i + 2, 2 * k : 2 * k + 2] += sign * np.array([-r[1], r[0]])
                if j.actuated:
                    A[i + 2, 8] += sign
        for n in names:
            i = row[n]
            link = links[n]
            b[i : i + 2] = link.bar.mass * (link.com_acceleration - gravity)
            b[i + 2] = link.bar.inertia_planar * link.alpha
        for j in joints:  # friction moments: known loads, moved to the right-hand side
            w_rel = omega[j.child] - (omega[j.parent] if j.parent else 0.0)
            moment = -T[j.name] * math.tanh(w_rel / forces.SPEED_THRESHOLD)
            b[row[j.child] + 2] -= moment
            if j.parent:
                b[row[j.parent] + 2] += moment
        x = np.linalg.solve(A, b)
        new = {j.name: MU * RADIUS * float(np.linalg.norm(x[2 * k : 2 * k + 2])) for k, j in enumerate(joints)}
        change = max(abs(new[n] - T[n]) for n in T)
        T = new
        if change < 1e-15:
            break
    return float(x[8]), T


@pytest.mark.parametrize("crank", [(0.9, 2.0, 5.0), (2.4, -3.0, 1.0), (4.0, 0.5, -20.0)])
def test_efforts_with_friction_against_a_hand_computation(four_bar, crank):
    """The crank torque with friction at all four pins (the loop cut C included) and each pin's friction
    torque: mechkit's fixed point over the core's reactions against planar Newton-Euler by hand."""
    m = four_bar
    theta, rate, acc = crank
    state = motion(m.params, [theta], [rate], [acc])
    q = m.assemble([theta], guess=state.q)  # the closed form's (open) branch
    v = m.velocities(q, [rate])
    a = m.accelerations(q, v, [acc])
    ours = simulation.inverse_dynamics(m, q, v, a, [friction(m)])
    assert np.allclose(np.angle(np.exp(1j * (state.q - q))), 0.0, atol=1e-10) and np.allclose(state.qd, v, atol=1e-10)
    effort, torques = hand_newton_euler(state)
    assert ours.result.efforts["crank"] == pytest.approx(effort, rel=1e-9, abs=1e-12)  # both about -y (the URDF axis)
    for joint, size in torques.items():
        assert ours.friction[joint] == pytest.approx(size, rel=1e-9, abs=1e-14)
    assert ours.result.efforts["crank"] != pytest.approx(m.inverse_dynamics(q, v, a).efforts["crank"], rel=1e-3)
    assert ours.check < 1e-10


def test_friction_that_locks_is_refused_by_name(four_bar):
    """A friction coefficient far past self-locking: the fixed point diverges, and says so."""
    m = four_bar
    q = m.assemble([0.9])
    v = m.velocities(q, [2.0])
    a = m.accelerations(q, v, [5.0])
    cm = m.closure_model
    locking = forces.ReactionFriction(
        m.model, cm.joint_names, cm.kernel.cuts, {j: forces.PinFriction(80.0, 0.05) for j in cm.joint_names}
    )
    with pytest.raises(forces.FrictionLocks, match="locks"):
        simulation.inverse_dynamics(m, q, v, a, [locking])
