"""Holding a body's pose: the spherical platform kept level on a rolling and pitching carrier, a reachable
orientation recovered to 1e-10 rad, and the yaw it cannot cancel named."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit.base.exceptions import InvalidArgument
from mechkit.bases import with_base
from mechkit.bases.holding import hold_pose

UP = (0.0, 0.0, 1.0)
CARRIER = {"base_roll": 0.1, "base_pitch": -0.08, "base_x": 0.3, "base_z": -0.2}  # ours


@pytest.fixture(scope="module")
def moving(load_cached):
    return with_base(load_cached("spherical_2dof"), "moving")


def _platform(mech, q):
    data = mech.model.createData()
    pin.framesForwardKinematics(mech.model, data, q)
    return data.oMf[mech.model.getFrameId("platform")]


def test_level_on_a_rolling_pitching_carrier(moving):
    held = hold_pose(moving, "platform", axis=(UP, UP), base_pose=CARRIER)
    z = _platform(moving, held.q).rotation[:, 2]
    assert held.tilt < 1e-10 and np.arccos(min(z[2], 1.0)) < 1e-7  # arccos near 1 loses half the digits
    assert np.abs(moving.closure_residual(held.q)).max() < 1e-10
    assert held.unreachable == ()
    tilted = _platform(moving, moving.assembly({**CARRIER, **{j: held.inputs[j] * 0.9 for j in held.inputs}}).q)
    assert tilted.rotation[2, 2] < 1 - 1e-6  # other inputs do not hold it level


def test_a_reachable_orientation_is_recovered(moving):
    """The orientation some inputs give on the carrier: found again from home, to 1e-10 rad."""
    chosen = {"r11": 0.9, "r21": 1.05}
    target = _platform(moving, moving.assembly({**CARRIER, **chosen}).q).rotation
    held = hold_pose(moving, "platform", rotation=target, base_pose=CARRIER)
    assert held.rotation_error < 1e-10
    assert pin.log3(target.T @ _platform(moving, held.q).rotation) == pytest.approx(np.zeros(3), abs=1e-10)
    assert held.inputs == pytest.approx(chosen, abs=1e-9)


def test_yaw_cannot_be_held_and_is_named(moving):
    """On a yawed carrier, the platform's heading follows the carrier's: a level platform with the world's
    heading is out of reach, and the answer names the rotation about the vertical, with what is left."""
    yawed = {**CARRIER, "base_yaw": 0.15}
    held = hold_pose(moving, "platform", rotation=np.eye(3), base_pose=yawed)
    ((kind, direction, left),) = held.unreachable
    assert kind == "rotation" and abs(direction[2]) > 0.99 and abs(left) > 0.1
    assert held.rotation_error == pytest.approx(abs(left), rel=1e-6)
    assert hold_pose(moving, "platform", axis=(UP, UP), base_pose=yawed).tilt < 1e-10


@pytest.mark.parametrize(
    ("kwargs", "arg"),
    [
        ({"frame": "no_such_link", "axis": (UP, UP)}, "frame"),
        ({"frame": "platform"}, "rotation"),
        ({"frame": "platform", "rotation": np.ones((3, 3))}, "rotation"),
        ({"frame": "platform", "axis": (UP, (0, 0, 0))}, "axis"),
        ({"frame": "platform", "axis": (UP, UP), "base_pose": {"heave": 0.1}}, "base_pose"),
    ],
)
def test_refusals_name_the_argument(moving, kwargs, arg):
    with pytest.raises(InvalidArgument, match=arg):
        hold_pose(moving, **kwargs)
