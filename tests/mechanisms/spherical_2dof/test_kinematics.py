"""`mechkit.mechanisms.spherical_2dof.kinematics`: the paper's equations as printed, both IK branches,
the Jacobian against Pinocchio, the printed FK step, limb angles against the model's frames."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.spherical_2dof import Spherical2DofParams
from mechkit.mechanisms.spherical_2dof import kinematics as kin
from mechkit.mechanisms.spherical_2dof.joint_state import state
from mechkit.mechanisms.spherical_2dof.kinematics import BRANCHES
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude, cone_times

P = Spherical2DofParams()


def test_middle_axis_is_eq4_as_printed():
    """w_i of our chain equals the third column (a13, a23, a33) printed in eq. (4)."""
    s, c = np.sin, np.cos
    a1, b = P.alpha1, P.beta
    for i, eta in ((1, P.eta11), (2, P.eta12)):
        for th in np.linspace(-3, 3, 7):
            printed = [
                -s(a1) * c(eta) * s(th) + s(a1) * s(eta) * c(b) * c(th) + s(eta) * s(b) * c(a1),
                -s(a1) * s(eta) * s(th) - s(a1) * c(eta) * c(b) * c(th) - c(a1) * c(eta) * s(b),
                s(b) * c(th) * s(a1) - c(b) * c(a1),
            ]
            np.testing.assert_allclose(kin.middle_axis(P, i, th), printed, atol=1e-15)


def test_ik_both_branches_close_eq7_and_differ():
    for phi in cone_attitude(cone_times(9))[0]:
        plus, minus = (kin.inverse_kinematics(P, phi, (k, k)) for k in (1, -1))
        assert np.abs(kin.constraint(P, plus, phi)).max() < 1e-14
        assert np.abs(kin.constraint(P, minus, phi)).max() < 1e-14
        assert np.abs(plus - minus).min() > 0.5


def test_unreachable_attitude_raises():
    with pytest.raises(InvalidParameters) as err:
        kin.inverse_kinematics(P, np.radians([-40.0, 0.0]))
    assert err.value.name == "phi"


def test_jacobian_against_pinocchio_velocity_projection(mech):
    """Hooke rates from the core's closure Jacobian equal J theta' (J = -B^-1 A)."""
    for phi in cone_attitude(cone_times(6))[0]:
        theta = kin.inverse_kinematics(P, phi, BRANCHES)
        q, _, _ = state(mech, phi, np.zeros(2), np.zeros(2))
        for rates in np.eye(2):
            v = mech.velocities(q, rates)
            hooke = v[[mech.v_index("hooke_roll"), mech.v_index("hooke_pitch")]]
            np.testing.assert_allclose(hooke, kin.jacobian(P, theta, phi) @ rates, atol=1e-12)


def test_cut_joint_angle_matches_pinocchio_frames(mech):
    """The cut frames of r{i}3 differ by Rz(theta_i3) of `kin.limb_angles` (xacro = our chain)."""
    import pinocchio as pin

    for phi in cone_attitude(cone_times(4))[0]:
        theta = kin.inverse_kinematics(P, phi, BRANCHES)
        q, _, _ = state(mech, phi, np.zeros(2), np.zeros(2))
        pin.framesForwardKinematics(mech.model, mech.data, q)
        for k, i in enumerate((1, 2)):
            rot = [mech.data.oMf[mech.model.getFrameId(f)].rotation for f in (f"link{i}2_C", f"platform_C{i}")]
            np.testing.assert_allclose(
                rot[0].T @ rot[1], kin.rot_z(kin.limb_angles(P, i, theta[k], phi)[1]), atol=1e-14
            )
