"""The ten-bar (patent CN105975733) as a mechanism: its topology and mobility, the deployment as its
motion law."""

from __future__ import annotations

import numpy as np

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
