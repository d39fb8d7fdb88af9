"""The isolation chart's pieces: the holding table, and the simulated residual tilt against the linear
servo's |1 - H(jw)| where the motors' rotors dominate the inertia the drives see."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidArgument
from mechkit.bases.isolation import holding_table, isolation_point, on_carrier, servo_theory
from mechkit.bases.servo import reflected_inertia

UP = ((0.0, 0.0, 1.0), (0.0, 0.0, 1.0))
A = np.radians(5.0)  # the carrier's roll amplitude (ours)


@pytest.fixture(scope="module")
def carried(load_cached):
    mech = on_carrier(load_cached("spherical_2dof"), 0.05)  # a 0.05 kg m^2 reflected rotor (ours)
    return mech, holding_table(mech, "platform", UP, A)


def test_holding_table_levels_the_platform(carried):
    mech, table = carried
    assert table.worst_tilt < 1e-10
    commands = table.command(0.5 * A, 0.0)
    q = mech.assembly({"base_roll": 0.5 * A, **{j: c[0] for j, c in commands.items()}}).q
    assert abs(_tilt(mech, q)) < 1e-8  # between the tabulated angles: the spline's error


def _tilt(mech, q):
    import pinocchio as pin

    data = mech.model.createData()
    pin.framesForwardKinematics(mech.model, data, q)
    return data.oMf[mech.model.getFrameId("platform")].rotation[1, 2]


def test_residual_tilt_follows_the_servo_at_its_bandwidth(carried):
    """At the servos' bandwidth the platform keeps |1 - H| = 0.71 of the carrier's tilt by the linear servo;
    the simulation, with gravity and the links' 11 % of the inertia, within 15 % of it."""
    mech, table = carried
    point = isolation_point(mech, table, A, frequency=2.0, bandwidth=2.0)
    assert point.theory == pytest.approx(1 / 1.4, rel=1e-12)
    assert point.ratio == pytest.approx(point.theory, rel=0.15)
    assert point.energy_drift < 1e-4


def test_servo_theory_limits():
    assert servo_theory(0.01, 2.0) == pytest.approx((0.01 / 2.0) ** 2, rel=1e-3)
    assert servo_theory(200.0, 2.0) == pytest.approx(1.0, rel=1e-3)


def test_rotor_inertia_adds_to_what_the_drive_sees(load_cached):
    grounded = load_cached("spherical_2dof")
    bare, rotor = on_carrier(grounded, 0.0), on_carrier(grounded, 0.05)
    assert reflected_inertia(rotor, "r11") - reflected_inertia(bare, "r11") == pytest.approx(0.05, rel=1e-12)
    assert not grounded.model.armature.any()
    with pytest.raises(InvalidArgument, match="rotor_inertia"):
        on_carrier(grounded, -1.0)
    with pytest.raises(InvalidArgument, match="amplitude"):
        holding_table(bare, "platform", UP, 0.0)
