"""`mechkit.mechanisms.spherical_2dof.joint_state`: the analytic state closes the model's loops at
every order."""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.spherical_2dof.joint_state import state
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude, cone_times


def test_analytic_state_satisfies_pinocchio_closure(mech):
    t = cone_times(8)
    for phi, phi_d, phi_dd in zip(*cone_attitude(t)):
        q, v, a = state(mech, phi, phi_d, phi_dd)
        assert np.abs(mech.closure_residual(q)).max() < 1e-13
        assert np.abs(mech.closure_jacobian(q) @ v).max() < 1e-12
        assert np.abs(mech.closure_jacobian(q) @ a + mech.closure_drift(q, v)).max() < 1e-11
