"""`mechkit.mechanisms.parallel_2t1r.joint_state`: every forward solution of the paper's example, written
on the joints, is where the closure solve lands."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import ClosureNotConverged, InvalidParameters
from mechkit.mechanisms.parallel_2t1r import kinematics as kin
from mechkit.mechanisms.parallel_2t1r.branch import EXAMPLE_INPUTS
from mechkit.mechanisms.parallel_2t1r.joint_state import joint_coordinates
from mechkit.mechanisms.parallel_2t1r.rates import at_rest


def _analytic_q(mech, pose: kin.Pose, theta4: float) -> np.ndarray:
    s = at_rest(pose, EXAMPLE_INPUTS, theta4)
    q = mech.neutral()
    for joint, (value, _, _) in joint_coordinates(mech.params, s).items():
        q[mech.q_index(joint)] = value
    return q


def test_example_assembles_into_every_forward_solution(mech):
    """Each FK pose with each theta_4 root: Pinocchio's closure solve from a guess 0.05 rad away
    lands on the analytic configuration. The one pose limb III cannot reach does not assemble."""
    rng = np.random.default_rng(3)
    assembled = 0
    for sol in kin.forward_kinematics(mech.params.dims, EXAMPLE_INPUTS):
        try:
            roots, _ = kin.follower_angles(mech.params.dims, sol.pose)
        except InvalidParameters:
            with pytest.raises(ClosureNotConverged):
                q0 = _analytic_q(mech, sol.pose, 0.0)
                mech.assemble(EXAMPLE_INPUTS, guess=q0 + rng.uniform(-0.05, 0.05, q0.size), max_iter=40)
            continue
        for theta4 in roots:
            exact = _analytic_q(mech, sol.pose, theta4)
            q = mech.assemble(EXAMPLE_INPUTS, guess=exact + rng.uniform(-0.05, 0.05, exact.size))
            assert np.max(np.abs(mech.closure_residual(q))) < 1e-12
            np.testing.assert_allclose(np.angle(np.exp(1j * (q - exact))), 0.0, atol=1e-10)
            assembled += 1
    assert assembled == 6
