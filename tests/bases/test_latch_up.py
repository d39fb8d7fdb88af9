"""The latch-up impulses: Carnot's energy of the jump equals what the simulator's impact dissipates, and a
jump that leaves the closures is refused."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidArgument
from mechkit.bases.latch_up import latch_up


def test_carnot_energy_is_the_impacts_and_the_impulses_balance(load_cached):
    """The ten-bar's rocker R5 caught at -0.08 rad on the ground (a 4 s deployment): 1/2 dv^T M dv equals
    the impact's dissipated energy; the latch impulse stops R5's momentum (its impulse opposes its rate)."""
    import mechkit
    from mechkit.mechanisms.ten_bar.scenes import latch_up_in_orbit

    runs = latch_up_in_orbit(mechkit.load("ten_bar", deploy_time=4.0))
    for name in ("ground", "orbit"):
        when, rate, shock, dissipated = runs[name]
        assert 0 < when < 1 and rate > 1.0
        assert shock.energy == pytest.approx(dissipated, rel=1e-9)
        assert shock.driven["R5"] < 0  # against the rocker's motion
    orbit = runs["orbit"][2]
    assert np.abs(orbit.reactions["base_free"]).max() < 1e-9  # nothing outside pushes the bus
    assert runs["orbit"][2].energy > 2 * runs["ground"][2].energy  # no weight to slow the rocker in orbit


def test_a_jump_off_the_closures_is_refused(load_cached):
    mech = load_cached("four_bar")
    dv = np.zeros(mech.model.nv)
    dv[0] = 1.0
    with pytest.raises(InvalidArgument, match="closures"):
        latch_up(mech, mech.home_q, np.zeros(mech.model.nv), dv, ["crank"])
