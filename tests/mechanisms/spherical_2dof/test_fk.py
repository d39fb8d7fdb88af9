"""`mechkit.mechanisms.spherical_2dof.fk`: the basins of the three forward kinematics."""

from __future__ import annotations

import math

import numpy as np

from mechkit.loading import load
from mechkit.mechanisms.spherical_2dof.fk import NEAR_SINGULAR, REGULAR, basin_study


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
