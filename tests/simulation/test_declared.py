"""`mechkit.simulation.declared`: what the registered four-bar's description declares (no force element,
+-25 rad limits with the restitution asked for, motors without envelope), and a torque off the actuators
refused by name."""

from __future__ import annotations

import pytest

from mechkit import simulation
from mechkit.base.exceptions import InvalidParameters


def test_the_descriptions_forces_and_limits(four_bar):
    """The registered four-bar declares no damper, friction or spring (no element) and +-25 rad limits on
    its joints, with the restitution asked for; a torque off the actuators is refused by name."""
    assert simulation.default_forces(four_bar) == []
    limits = simulation.file_limits(four_bar, restitution=0.3)
    assert {lim.joint for lim in limits} <= set(four_bar.model.names[1:]) and "crank" in {lim.joint for lim in limits}
    assert all((lim.lower, lim.upper, lim.restitution) == (-25.0, 25.0, 0.3) for lim in limits)
    motors = simulation.torque_motors(four_bar, {"crank": 1.0})
    assert [m.name for m in motors] == ["crank"] and (motors[0].stall, motors[0].no_load) == (1e6, 1e3)
    with pytest.raises(InvalidParameters) as err:
        simulation.torque_motors(four_bar, {"rocker": 1.0})
    assert err.value.name == "torques"
