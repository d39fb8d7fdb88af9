"""`mechkit.simulation.declared`: what the registered four-bar's description declares (no force element,
+-25 rad limits on the rocker and none that stops the full-turn crank, with the restitution asked for, motors
without envelope), and a torque off the actuators refused by name."""

from __future__ import annotations

import pytest

from mechkit import simulation
from mechkit.base.exceptions import InvalidParameters


def test_the_descriptions_forces_and_limits(four_bar):
    """The registered four-bar declares no damper, friction or spring (no element), +-25 rad on its rocker and
    +-1e9 rad (no stop) on its full-turn crank and coupler, with the restitution asked for; a torque off the
    actuators is refused by name."""
    assert simulation.default_forces(four_bar) == []
    limits = simulation.file_limits(four_bar, restitution=0.3)
    assert {lim.joint for lim in limits} <= set(four_bar.model.names[1:]) and "crank" in {lim.joint for lim in limits}
    full_turn = {"crank", "coupler"}  # a Grashof crank-rocker's: no stop (xacro/four_bar.urdf.xacro)
    assert all(
        (lim.lower, lim.upper, lim.restitution) == ((-1e9, 1e9, 0.3) if lim.joint in full_turn else (-25.0, 25.0, 0.3))
        for lim in limits
    )
    motors = simulation.torque_motors(four_bar, {"crank": 1.0})
    assert [m.name for m in motors] == ["crank"] and (motors[0].stall, motors[0].no_load) == (1e6, 1e3)
    with pytest.raises(InvalidParameters) as err:
        simulation.torque_motors(four_bar, {"rocker": 1.0})
    assert err.value.name == "torques"


def test_a_driven_crank_turns_on_without_a_stop(four_bar):
    """0.5 N m on the crank for 0.6 s: it turns beyond the +-25 rad the template once gave it, and nothing stops
    it (no limit event), as a crank-rocker's crank should."""
    run = four_bar.simulate(0.6, torques={"crank": 0.5}, reactions=False, rtol=1e-6, atol=1e-8)
    assert run.motion.q[-1, four_bar.q_index("crank")] > 30.0
    assert run.events == ()
