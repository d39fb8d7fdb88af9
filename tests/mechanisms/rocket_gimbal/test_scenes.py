"""`mechkit.mechanisms.rocket_gimbal.scenes`: thrust through the swing centre loads the bearings, not
the servos."""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.rocket_gimbal.joint_state import joint_state
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene, thrust_fext


def test_thrust_through_the_swing_centre_loads_the_bearings_not_the_servos(mech):
    scene, idle = SwingScene(), SwingScene(thrust=0.0)
    motion = scene.motion(mech.params, 0.2)
    q, v, a = joint_state(mech, motion)
    loaded = mech.inverse_dynamics(q, v, a, fext=thrust_fext(mech, q, scene))
    free = mech.inverse_dynamics(q, v, a, fext=thrust_fext(mech, q, idle))
    for name in mech.actuated:
        assert np.isclose(loaded.efforts[name], free.efforts[name], rtol=1e-9)
    nozzle = mech.data.oMi[mech.model.getJointId("engine_hinge")].rotation[:, 2]
    thrust = -scene.thrust * nozzle
    for joint in ("bracket_hinge", "engine_hinge"):
        change = loaded.reactions[joint].wrench - free.reactions[joint].wrench
        assert np.allclose(change[:3], -thrust, rtol=0, atol=1e-6 * scene.thrust)
        assert np.allclose(change[3:], 0.0, atol=1e-6 * scene.thrust)


def test_in_flight_is_the_bench_under_the_equivalent_gravity(mech):
    """The swing on a vehicle accelerating at 2 g under thrust: the actuator forces are those of a fixed
    gimbal under g - a with the same thrust (the moving base against the fixed one), and the thrust adds
    nothing to them (it passes through the swing centre)."""
    from mechkit import motion
    from mechkit.bases import with_base
    from mechkit.mechanisms.rocket_gimbal.scenes import AXIAL_ACCELERATION, in_flight

    runs = in_flight(mech)
    scene = SwingScene()
    law = motion.from_scene(mech, "swing")
    heavy = with_base(mech, "fixed", gravity=(0.0, 0.0, -9.81 - AXIAL_ACCELERATION))
    equivalent = motion.study(heavy, law, loads=lambda m, q, t: thrust_fext(m, q, scene))
    unthrusted = motion.study(heavy, law)
    scale = np.abs(equivalent.efforts).max()
    assert np.abs(runs["flight"].efforts[:, 6:] - equivalent.efforts).max() < 1e-9 * scale
    assert np.abs(equivalent.efforts - unthrusted.efforts).max() < 1e-9 * scale
    assert np.abs(runs["bench"].efforts - equivalent.efforts).max() > 0.1 * scale  # 3 g is not 1 g
