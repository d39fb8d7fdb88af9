"""`mechkit.mechanisms.parallel_2t1r.branch`: the sixteen configurations of the assembled pose."""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.parallel_2t1r import kinematics as kin
from mechkit.mechanisms.parallel_2t1r.branch import EXAMPLE_INPUTS, assembled_pose
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams

P = Parallel2T1RParams()


D = P.dims


def test_sixteen_configurations_of_the_assembled_pose():
    pose, _, _ = assembled_pose(D, EXAMPLE_INPUTS)
    roots, _ = kin.follower_angles(D, pose)
    configs = [np.append(inputs, t4) for inputs in kin.inverse_kinematics(D, pose) for t4 in roots]
    assert len({tuple(np.round(c, 9)) for c in configs}) == 16
    for c in configs:
        assert np.max(np.abs(kin.loop_residuals(D, c, pose))) < 1e-12
