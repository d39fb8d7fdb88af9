"""`mechkit.simulation.floating`: on a free-flyer root the simulator takes "kkt" unless a method is asked
for (and says so), and records the whole system's momentum, which it conserves with no gravity."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.bases import with_base
from mechkit.bases.momentum import momentum
from mechkit.simulation.floating import FLOATING_NOTE, default_dynamics, free_flyer_root

W = 2 * np.pi  # one 1 s cycle of the inputs (ours)


@pytest.fixture(scope="module")
def platform(load_cached):
    return load_cached("spherical_2dof")


@pytest.fixture(scope="module")
def floating(platform):
    return with_base(platform, "floating", base_inertia=(20.0, (0.5, 0.6, 0.7)), gravity=(0, 0, 0))


def _run(mech, duration=0.6, **options):
    home = mech.spec.home(mech.params)
    r11, r21 = home["r11"], home["r21"]

    def law(t):
        s, c, a = 0.15 * (1 - np.cos(W * t)), 0.15 * W * np.sin(W * t), 0.15 * W * W * np.cos(W * t)
        return np.array([r11 + s, r21 - 2 * s]), np.array([c, -2 * c]), np.array([a, -2 * a])

    return mech.simulate(duration, inputs=law, input_names=["r11", "r21"], rtol=1e-8, atol=1e-10, **options)


def test_the_root_decides_the_default_dynamics(platform, floating):
    assert free_flyer_root(floating.model) and not free_flyer_root(platform.model)
    assert default_dynamics(floating.model, False) == ("kkt", FLOATING_NOTE)
    assert default_dynamics(platform.model, False) == ("proximal", "")
    assert default_dynamics(platform.model, True) == ("kkt", "")


def test_a_floating_run_takes_kkt_and_records_its_momentum(floating):
    """Default options on the 20 kg bus (proximal there: 607 steps, balance 3.5e-5; kkt: 42 steps, 2e-9):
    kkt, said in the summary; the momentum at every sample is `mechkit.bases.momentum`'s, it stays at its
    start (zero) to 1e-8 of the bodies' momentum (measured 5e-10) and the summary prints its drift."""
    r = _run(floating, reactions=False)
    assert r.integrator["dynamics"] == "kkt" and r.integrator["dynamics_note"] == FLOATING_NOTE
    lines = r.summary()
    assert f"dynamics: {FLOATING_NOTE}" in lines and any(line.startswith("momentum drift:") for line in lines)
    again = momentum(floating, r.t, r.motion.q, r.motion.v)
    np.testing.assert_array_equal(r.momentum.linear, again.linear)
    np.testing.assert_array_equal(r.momentum.angular, again.angular)
    drift = r.momentum.drift()
    assert r.momentum.scale > 0.1  # kg m/s: the bodies move
    assert drift["relative_linear"] <= 1e-8 and drift["angular"] <= 1e-8 * r.momentum.scale
    assert drift["com"] <= 1e-9  # m: the centre of mass stays still


def test_a_method_asked_for_is_kept(floating):
    r = _run(floating, 0.05, dynamics="proximal", reactions=False)
    assert r.integrator["dynamics"] == "proximal" and r.integrator["dynamics_note"] == ""
    assert not any(line.startswith("dynamics:") for line in r.summary())


def test_a_fixed_root_records_no_momentum(platform):
    r = _run(platform, 0.05, reactions=False)
    assert r.momentum is None and r.integrator["dynamics"] == "proximal"
    assert not any(line.startswith("momentum drift:") for line in r.summary())
