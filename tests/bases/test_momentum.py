"""A floating system with no gravity conserves its momentum to the integrator's tolerance, and its centre
of mass stays still; the same motion on a fixed base does not (the ground pushes)."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidArgument
from mechkit.bases import with_base
from mechkit.bases.momentum import momentum

W = 2 * np.pi  # one 1 s cycle of the inputs (ours)


def _cycle(home):
    """r11 and r21 leave home and come back, at rest at both ends."""

    def law(t):
        s, c, a = 0.15 * (1 - np.cos(W * t)), 0.15 * W * np.sin(W * t), 0.15 * W * W * np.cos(W * t)
        return np.array([home["r11"] + s, home["r21"] - 2 * s]), np.array([c, -2 * c]), np.array([a, -2 * a])

    return law


def _run(mech, rtol):
    home = mech.spec.home(mech.params)
    law = _cycle({j: home[j] for j in ("r11", "r21")})
    r = mech.simulate(0.6, inputs=law, input_names=["r11", "r21"], dynamics="kkt", rtol=rtol, atol=rtol * 1e-2)
    return momentum(mech, r.t, r.motion.q, r.motion.v)


@pytest.fixture(scope="module")
def floating(load_cached):
    return with_base(load_cached("spherical_2dof"), "floating", base_inertia=(20.0, (0.5, 0.6, 0.7)), gravity=(0, 0, 0))


def test_floating_system_conserves_momentum(floating):
    """From rest: p and h_O stay 0 and the centre of mass still, the drift shrinking with the tolerance."""
    loose, tight = _run(floating, 1e-6).drift(), _run(floating, 1e-9).drift()
    assert tight["relative_linear"] < 1e-9
    assert tight["angular"] < 1e-10  # kg m^2/s, of a system whose bodies carry 0.2 kg m/s at a lever of 0.1 m
    assert tight["com"] < 1e-11
    assert tight["linear"] < 1e-2 * loose["linear"] and tight["com"] < 1e-2 * loose["com"]


def test_a_fixed_base_does_not(load_cached):
    """The same inputs on the ground: the ground's reactions change the momentum (the check can fail)."""
    fixed = with_base(load_cached("spherical_2dof"), "fixed", gravity=(0, 0, 0))
    assert _run(fixed, 1e-9).drift()["relative_linear"] > 1e-2


def test_momentum_refuses_mismatched_samples(floating):
    q = np.tile(floating.home_q, (3, 1))
    with pytest.raises(InvalidArgument, match="t"):
        momentum(floating, np.zeros(2), q, np.zeros((3, floating.model.nv)))
    with pytest.raises(InvalidArgument, match="v"):
        momentum(floating, np.zeros(3), q, np.zeros((2, floating.model.nv)))
