"""The pipeline against the independent closed-form planar references (numpy Newton-Euler)."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.validation.planar_closed_form import five_bar, four_bar
from mechkit.validation.planar_newton_euler import newton_euler

T = np.linspace(0.0, 2.0, 41)


def crank_law(t):
    """A smooth crank motion covering more than a full turn: angle, rate, acceleration."""
    return 0.6 + 4.0 * t + 0.3 * np.sin(3 * t), 4.0 + 0.9 * np.cos(3 * t), -2.7 * np.sin(3 * t)


def five_bar_law(t):
    th = np.array([2.0 + 0.3 * np.sin(2 * t), 1.1 + 0.25 * np.sin(3 * t + 0.4)])
    rate = np.array([0.6 * np.cos(2 * t), 0.75 * np.cos(3 * t + 0.4)])
    acc = np.array([-1.2 * np.sin(2 * t), -2.25 * np.sin(3 * t + 0.4)])
    return th, rate, acc


def _wrap(x):
    return (x + np.pi) % (2 * np.pi) - np.pi


def _samples(name, load_cached):
    m = load_cached(name)
    q = m.home_q
    for t in T:
        if name == "four_bar":
            th, rate, acc = crank_law(t)
            state = four_bar(th, rate, acc)
        else:
            th, rate, acc = five_bar_law(t)
            state = five_bar(tuple(th), tuple(rate), tuple(acc))
        q = m.assemble(np.atleast_1d(th), guess=q)
        v = m.velocities(q, np.atleast_1d(rate))
        a = m.accelerations(q, v, np.atleast_1d(acc))
        yield m, state, q, v, a


@pytest.mark.parametrize("name", ["four_bar", "five_bar"])
def test_kinematics_match_closed_form(name, load_cached):
    for m, state, q, v, a in _samples(name, load_cached):
        order = [m.q_index(j) for j in state.coordinates]
        assert np.max(np.abs(_wrap(q[order] - state.q))) < 1e-10
        assert np.max(np.abs(v[order] - state.qd)) < 1e-10 * max(1.0, np.max(np.abs(state.qd)))
        assert np.max(np.abs(a[order] - state.qdd)) < 1e-10 * max(1.0, np.max(np.abs(state.qdd)))


@pytest.mark.parametrize("name", ["four_bar", "five_bar"])
def test_torques_and_every_pin_reaction_match_newton_euler(name, load_cached):
    worst = 0.0
    for m, state, q, v, a in _samples(name, load_cached):
        expected = newton_euler(state)
        got = m.inverse_dynamics(q, v, a)
        scale = max(np.max(np.abs(w)) for w in expected.reactions.values())
        assert set(got.reactions) == set(expected.reactions)
        for joint, wrench in expected.reactions.items():
            r = got.reactions[joint]
            # in-plane forces and the moment about the axis are determinate; compare those
            np.testing.assert_array_equal(r.determinate, [True, False, True, False, True, False])
            worst = max(worst, np.max(np.abs(r.wrench[[0, 2, 4]] - wrench[[0, 2, 4]])) / scale)
        for joint, effort in expected.efforts.items():
            worst = max(worst, abs(got.efforts[joint] - effort) / scale)
    assert worst < 1e-9
