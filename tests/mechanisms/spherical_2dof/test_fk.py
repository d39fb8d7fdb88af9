"""`mechkit.mechanisms.spherical_2dof.fk`: the paper's printed step does not converge (ours does), Newton
from a hopeless start raises, and the basins of the three forward kinematics."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechkit.base.exceptions import ClosureNotConverged, InvalidParameters
from mechkit.loading import load
from mechkit.mechanisms.spherical_2dof import Spherical2DofParams
from mechkit.mechanisms.spherical_2dof import kinematics as kin
from mechkit.mechanisms.spherical_2dof.fk import NEAR_SINGULAR, REGULAR, basin_study, fk_newton, fk_paper
from mechkit.mechanisms.spherical_2dof.kinematics import BRANCHES
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude

P = Spherical2DofParams()


def test_basin_study():
    """Regular pose: every method finds the answer from 1 and 5 deg away; at 20 deg the paper's
    method loses starts (its iterates leave the workspace, where InvKin is undefined) that Newton
    keeps. 0.4 deg from the forward singularity the other assembly mode (the mirror root across
    det B = 0) captures starts 1 deg away, from every method."""
    mech = load("spherical_2dof")
    regular = basin_study(mech, REGULAR, np.radians([1.0, 5.0, 20.0]), 12)
    table = {(r.method, round(math.degrees(r.radius))): r for r in regular}
    for method in ("paper", "newton", "closure"):
        assert table[method, 1].found == table[method, 5].found == 1.0
    assert table["paper", 20].failed > 0.0 and table["newton", 20].found > table["paper", 20].found
    near = basin_study(mech, NEAR_SINGULAR, np.radians([0.1, 1.0]), 12)
    for r in near:
        assert (r.found == 1.0) if r.radius < 0.01 else (r.elsewhere > 0.0)


def test_printed_fk_step_does_not_converge():
    """The step as printed, -J^-1 (theta_d - theta_k), wanders off; J (theta_d - theta_k) converges."""
    target = cone_attitude(0.3)[0]
    theta_d = kin.inverse_kinematics(P, target, BRANCHES)
    phi = target + 0.02
    for _ in range(30):
        try:
            theta = kin.inverse_kinematics(P, phi, BRANCHES)
        except InvalidParameters:
            break
        phi = phi - np.linalg.solve(kin.jacobian(P, theta, phi), theta_d - theta)
    assert np.abs(phi - target).max() > 1e-3
    assert np.abs(fk_paper(P, theta_d, target + 0.02).phi - target).max() < 1e-12


def test_closure_fk_from_a_hopeless_start_raises(mech):
    theta_d = kin.inverse_kinematics(P, np.zeros(2))
    with pytest.raises(ClosureNotConverged):
        fk_newton(P, theta_d, np.radians([170.0, 80.0]), max_iter=5)
