"""The 2T1R's `mechkit report` rows: the paper's example through FK and IK, and the three inverse
dynamics methods against each other along the motion law."""

from __future__ import annotations

import numpy as np

from mechkit.mechanism import Mechanism
from mechkit.mechanisms.parallel_2t1r.branch import EXAMPLE_INPUTS
from mechkit.mechanisms.parallel_2t1r.compare import compare_along
from mechkit.mechanisms.parallel_2t1r.kinematics import forward_kinematics, inverse_kinematics, loop_residuals
from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_DURATION


def self_checks(mech: Mechanism) -> dict[str, float]:
    """`mechkit report` rows: FK/IK of the paper's example and SOC / classic vs Pinocchio (26 samples).

    Args:
        mech: the 2T1R.

    Returns:
        Check name (with its unit) -> worst residual or relative error.
    """
    d = mech.params.dims
    worst_residual, worst_trip = 0.0, 0.0
    for pose in (s.pose for s in forward_kinematics(d, EXAMPLE_INPUTS)):
        sets = inverse_kinematics(d, pose)
        for sol in sets:
            residual = np.max(np.abs(loop_residuals(d, np.append(sol, 0.0), pose)[:3]))
            worst_residual = max(worst_residual, residual)
        trip = np.min(np.abs(np.angle(np.exp(1j * (sets - EXAMPLE_INPUTS)))).max(axis=1))
        worst_trip = max(worst_trip, float(trip))
    cmp = compare_along(mech, np.linspace(0.2, MOTION_DURATION, 25))
    rel = lambda m: float(np.nanmax(cmp.relative_error(m)))
    return {
        "analytic IK closure residual, paper example (m)": worst_residual,
        "FK -> IK round trip, paper example (rad)": worst_trip,
        "analytic vs Pinocchio joint angles, motion law (rad)": float(cmp.kinematics_error.max()),
        "SOC vs Pinocchio, torques + in-plane R23/R43 (rel.)": rel("soc"),
        "classic virtual work vs Pinocchio, torques (rel.)": rel("classic"),
    }
