"""`mechkit.mechanisms.tetra_3rr3uru.soc`: SOC virtual work against constrained RNEA along the fold;
its independent motion against Pinocchio's forward kinematics."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.tetra_3rr3uru import soc

from ..truss.paper import TIMES


@pytest.mark.parametrize("i", range(len(TIMES)))
def test_soc_agrees_with_constrained_rnea(unit, unit_fold, i):
    sample = unit_fold[i]
    reference = unit.inverse_dynamics(sample.q, sample.v, sample.a)
    result = soc.solve(unit, sample.t)
    assert all(r.determinate.all() for r in reference.reactions.values())  # no redundant row in the unit
    effort_scale = max(abs(u) for u in reference.efforts.values())
    for joint, u in reference.efforts.items():
        assert result.efforts[joint] == pytest.approx(u, abs=1e-8 * effort_scale)
    scale = max(np.abs(r.wrench).max() for r in reference.reactions.values())
    for joint, r in reference.reactions.items():
        np.testing.assert_allclose(result.reactions[joint], r.wrench, atol=1e-8 * scale, err_msg=joint)


def test_soc_independent_motion_matches_pinocchio_forward_kinematics(unit, unit_fold):
    import pinocchio as pin

    motion = soc.UnitMotion(unit.params)
    for sample in unit_fold:
        R, origin = motion.poses(sample.t)
        pin.forwardKinematics(unit.model, unit.data, sample.q)
        for joint in motion.joints:
            placement = unit.data.oMi[unit.model.getJointId(joint.name)]
            np.testing.assert_allclose(placement.rotation, R[joint.child], atol=1e-9)
            np.testing.assert_allclose(placement.translation, origin[joint.child], atol=1e-9)
