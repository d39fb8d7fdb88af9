"""`mechkit.mechanisms.ten_bar.limits`: the free passive motion, and the drift of the deployment
under each stabilisation."""

from __future__ import annotations

import pytest

from mechkit.base.exceptions import SingularConfiguration
from mechkit.mechanisms.ten_bar import limits as tl
from mechkit.simulation import DRIFT_TOL


def test_the_motors_alone_leave_the_passive_motion_free(mech):
    split = tl.kinematic_split(mech, mech.home_q)
    assert split.nullity == 1 and split.five_bar_nullity == 1
    assert abs(split.direction[mech.v_index("R5")]) > 1e-3  # the free motion moves the spring's rocker
    with pytest.raises(SingularConfiguration):
        mech.velocities(mech.home_q, {"R1": 0.1, "R3": 0.2})


def test_stabilisation_bounds_the_drift(mech):
    """Over the drift study's 5 s at 20 ms (the simulator's fifth-order steps: after 0.5 s the free drift
    is still within 1.3 times Baumgarte's, which its transient at the spring release sets), the free
    drift grows, Baumgarte's stays bounded, projection removes it (to the projection's drift tolerance,
    `simulation.DRIFT_TOL` = 1e-11 m: a smaller drift is left)."""
    free = tl.drift(mech, 5.0, 0.02, None, project=False).residual.max()
    baumgarte = tl.drift(mech, 5.0, 0.02, (100.0, 20.0), project=False).residual.max()
    projected = tl.drift(mech, 5.0, 0.02, None, project=True).residual.max()
    assert free > 10 * baumgarte and baumgarte > 1e3 * projected and projected <= DRIFT_TOL
