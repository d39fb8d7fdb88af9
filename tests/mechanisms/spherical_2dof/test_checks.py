"""`mechkit.mechanisms.spherical_2dof.checks`: the report rows (the cone round trip, the Jacobian, FK
three ways, the dynamics against SOC)."""

from __future__ import annotations

from mechkit.mechanisms.spherical_2dof import Spherical2DofParams, checks

P = Spherical2DofParams()


def test_cone_round_trip_ik_then_paper_fk():
    """IK gives the motor curves; the paper's FK of those curves returns the planned path."""
    attitude, marker = checks.cone_round_trip(P, 72)
    assert attitude < 1e-10 and marker < 1e-10


def test_jacobian_against_finite_differences():
    assert checks.jacobian_fd_error(P, 12) < 1e-7


def test_fk_methods_agree(mech):
    assert checks.fk_agreement(mech, 12) < 1e-10


def test_dynamics_pinocchio_vs_soc(mech):
    """Motor torques, the support moment and every joint's moment about O (the determinate parts)."""
    errors = checks.dynamics_agreement(mech, 24)
    assert errors["efforts"] < 1e-8 and errors["support"] < 1e-8 and errors["joints"] < 1e-8
    assert errors["consistency"] < 1e-10
