"""`mechkit.mechanisms.spherical_2dof.soc`: inertias, motor power, both branches against Pinocchio."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.spherical_2dof import Spherical2DofParams, soc
from mechkit.mechanisms.spherical_2dof import kinematics as kin
from mechkit.mechanisms.spherical_2dof.joint_state import state
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude, cone_times

P = Spherical2DofParams()


def test_soc_inertias_match_the_urdf(mech):
    """The SOC's body inertias (re-derived from the sizes) equal Pinocchio's parse of the xacro."""
    for name, (m, com, inertia) in soc.body_inertias(P).items():
        frame = mech.model.getFrameId(name)
        body = mech.model.inertias[mech.model.frames[frame].parentJoint]
        assert body.mass == pytest.approx(m, rel=1e-12)
        np.testing.assert_allclose(body.lever, com, atol=1e-15)
        np.testing.assert_allclose(body.inertia, inertia, atol=1e-15)


def test_motor_power_equals_rate_of_energy(mech):
    """sum tau_i theta_i1' = dE/dt (kinetic + gravity), E from the body motions, by central differences."""
    g, h = 9.81, 1e-4

    def energy(t: float) -> float:
        total = 0.0
        for b in soc.body_motions(P, *(x for x in cone_attitude(t))).values():
            v = kin.cross(b.omega, b.com)
            total += 0.5 * b.mass * v @ v + 0.5 * b.omega @ b.inertia @ b.omega + b.mass * g * b.com[2]
        return total

    for t in cone_times(6):
        phi, phi_d, phi_dd = cone_attitude(t)
        q, v, a = state(mech, phi, phi_d, phi_dd)
        rates = v[[mech.v_index(j) for j in mech.actuated]]
        reference = (energy(t + h) - energy(t - h)) / (2 * h)
        pin_power = rates @ [mech.inverse_dynamics(q, v, a).efforts[j] for j in mech.actuated]
        soc_power = rates @ [soc.solve(P, phi, phi_d, phi_dd).efforts[j] for j in mech.actuated]
        assert pin_power == pytest.approx(reference, abs=1e-8)
        assert soc_power == pytest.approx(reference, abs=1e-8)


def test_other_branch_closes_and_dynamics_agree(mech):
    """The other IK branch (-1, -1) is an assembly too; Pinocchio and SOC agree on it."""
    branches = (-1, -1)
    for phi, phi_d, phi_dd in zip(*cone_attitude(cone_times(4)), strict=True):
        q, v, a = state(mech, phi, phi_d, phi_dd, branches)
        assert np.abs(mech.closure_residual(q)).max() < 1e-13
        assert np.abs(mech.closure_jacobian(q) @ a + mech.closure_drift(q, v)).max() < 1e-11
        ref = mech.inverse_dynamics(q, v, a).efforts
        ours = soc.solve(P, phi, phi_d, phi_dd, branches).efforts
        for joint in mech.actuated:
            assert ours[joint] == pytest.approx(ref[joint], rel=1e-9, abs=1e-12)
