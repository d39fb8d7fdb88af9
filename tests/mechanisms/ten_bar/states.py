"""A ten-bar state mid-deployment, where the dynamics tests compare their routes."""

from __future__ import annotations

from mechkit.mechanisms.ten_bar import kinematics as tk


def mid_state(mech, rates=(0.05, -0.1, 0.2)):
    """(t, q, v) at 37 % of the deployment time: R1, R3, R5 at 0.7, -1.2, -0.3 rad moving at `rates` (rad/s)."""
    p = mech.params
    q = tk.full_solve(mech, {"R1": 0.7, "R3": -1.2, "R5": -0.3}, mech.home_q)
    v = mech.velocities(q, dict(zip(("R1", "R3", "R5"), rates)), inputs=("R1", "R3", "R5"))
    return 0.37 * p.deploy_time, q, v
