"""The ten-bar (patent CN105975733) as a mechanism: its topology and mobility, the deployment as its
motion law."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit.mechanisms.ten_bar import geometry as geo


def test_topology_is_the_patents(mech):
    assert mech.model.nv == 9 and mech.model.njoints - 1 == 9  # 9 moving links on 9 tree joints
    assert sorted(c.name for c in mech.closures) == sorted(geo.CUT_JOINTS)
    assert all(c.kind == "revolute" and c.rows == "planar" for c in mech.closures)
    pairs = list(mech.model.names[1:]) + [c.name for c in mech.closures]
    assert sorted(pairs) == sorted(geo.PAIRS) and len(pairs) == 12
    assert mech.actuated == ("R1", "R3")
    gruebler = 3 * 9 - 2 * 12
    assert gruebler == mech.spec.gruebler_dof == mech.mobility().dof == 3
    assert mech.mobility().redundant == 0


def test_deployment_law_is_the_deployment_scene(mech):
    """`SPEC.motion_laws["deploy"]`: the motors and the rocker along the deployment scene's poses, each a
    warm start, at the scene's times."""
    from mechkit import motion
    from mechkit.mechanisms.ten_bar.scenes import deployment_poses, deployment_times

    law = motion.from_law(mech, "deploy", 11)
    poses = np.array(deployment_poses(mech, 11))
    assert law.names == ("R1", "R3", "R5")
    assert np.array_equal(law.guesses, poses) and np.array_equal(law.t, deployment_times(mech, 11))
    assert np.array_equal(law.values, poses[:, [mech.q_index(j) for j in law.names]])


@pytest.mark.slow
def test_deployment_in_orbit_turns_the_bus_and_keeps_momentum(mech):
    """A 4 s deployment on a floating bus with no gravity: momentum kept, the bus turned about the plane's
    normal alone, the motor torques not the ground test's."""
    import mechkit
    from mechkit.bases import FLOATING_JOINT, momentum
    from mechkit.mechanisms.ten_bar.scenes import in_orbit

    quick = mechkit.load("ten_bar", deploy_time=4.0)
    runs = in_orbit(quick)
    floating, orbit = runs["floating"], runs["orbit"]
    drift = momentum(floating, orbit.t, orbit.motion.q, orbit.motion.v).drift()
    assert drift["relative_linear"] < 1e-8 and drift["com"] < 1e-8
    k = floating.q_index(FLOATING_JOINT) + 3
    turn = pin.log3(pin.Quaternion(orbit.motion.q[-1, k : k + 4]).matrix())
    normal = int(np.argmax(np.abs(turn)))
    assert abs(turn[normal]) > 1e-2 and np.delete(np.abs(turn), normal).max() < 1e-9
    ground = np.interp(orbit.t, runs["ground"].t, runs["ground"].motion.effort("R1"))
    assert np.nanmax(np.abs(orbit.motion.effort("R1") - ground)) > 1.0
