"""The 2-DOF spherical platform as a mechanism: its home assembly and mobility (spatial rows: six
redundant), `Mechanism.assemble` as its forward kinematics, the determinacy of its supports."""

from __future__ import annotations

import numpy as np

from mechkit.loading import load
from mechkit.mechanisms.spherical_2dof import SPEC, Spherical2DofParams
from mechkit.mechanisms.spherical_2dof import kinematics as kin
from mechkit.mechanisms.spherical_2dof.joint_state import state
from mechkit.mechanisms.spherical_2dof.kinematics import BRANCHES
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude, cone_times

P = Spherical2DofParams()


def test_home_assembles_with_two_dof(mech):
    assert np.abs(mech.closure_residual(mech.home_q)).max() < 1e-12
    mob = mech.mobility()
    assert mob.dof == 2 == SPEC.gruebler_dof and mob.redundant == 0


def test_spatial_rows_are_six_redundant_constraints():
    """With 5 spatial rows per cut the mobility stays 2 and 6 rows are redundant: the spatial
    Kutzbach-Gruebler count 6 (6 - 7 - 1) + 8 = -4 = 2 - 6 (the common constraints of a spherical linkage)."""
    mob = load("spherical_2dof", rows="spatial").mobility()
    assert (mob.dof, mob.redundant, mob.rows) == (2, 6, 10)


def test_mechanism_assemble_is_the_forward_kinematics(mech):
    """`Mechanism.assemble` from the motor angles (home guess) returns the planned attitude."""
    for phi in cone_attitude(cone_times(6))[0]:
        theta = kin.inverse_kinematics(P, phi, BRANCHES)
        q = mech.assemble(theta, guess=mech.home_q, tol=1e-13)
        found = q[[mech.q_index("hooke_roll"), mech.q_index("hooke_pitch")]]
        assert np.abs(found - phi).max() < 1e-10


def test_support_determinacy(mech):
    """Every body turns about O: forces at O are indeterminate, moments (about O) determinate."""
    phi, phi_d, phi_dd = (x[0] for x in cone_attitude(np.array([0.4])))
    q, v, a = state(mech, phi, phi_d, phi_dd)
    result = mech.inverse_dynamics(q, v, a)
    for name, reaction in result.reactions.items():
        assert not reaction.determinate[:3].any(), name
        assert reaction.determinate[3:].all(), name
    assert abs(result.reactions["hooke_roll"].wrench[3]) < 1e-12  # the roll axis X0 is free
