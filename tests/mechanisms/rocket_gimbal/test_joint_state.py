"""`mechkit.mechanisms.rocket_gimbal.joint_state`: the analytic motion satisfies the model's closure rows."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.rocket_gimbal.joint_state import joint_state
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene


@pytest.mark.parametrize("t", [0.05, 0.3, 0.77])
def test_analytic_motion_satisfies_pinocchios_closure_rows(mech, t):
    scene = SwingScene()
    q, v, a = joint_state(mech, scene.motion(mech.params, t))
    J = mech.closure_jacobian(q)
    assert np.abs(mech.closure_residual(q)).max() < 1e-12
    assert np.abs(J @ v).max() < 1e-12
    assert np.abs(J @ a + mech.closure_drift(q, v)).max() < 1e-11
    # Pinocchio's velocity / acceleration projection from the stroke rates gives the same motion
    rates = {j: v[mech.v_index(j)] for j in mech.actuated}
    accs = {j: a[mech.v_index(j)] for j in mech.actuated}
    assert np.allclose(mech.velocities(q, rates), v, atol=1e-12)
    assert np.allclose(mech.accelerations(q, v, accs), a, atol=1e-10)
