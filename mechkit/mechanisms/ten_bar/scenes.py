"""The ten-bar's scenes: the deployment, stowed to deployed, for animations and the gallery."""

from __future__ import annotations

import numpy as np

from mechkit.mechanism import Mechanism
from mechkit.mechanisms.ten_bar import dynamics as td


def deployment_poses(mechanism: Mechanism, frames: int = 120, dt: float = 0.02) -> list[np.ndarray]:
    """Stowed to deployed: the constrained-ABA deployment (RK4 with projection, step dt in s) sampled
    at `frames` poses, for animations."""
    trajectory = td.deploy(td.PinocchioDeployment(mechanism), mechanism.home_q, dt)
    picks = np.linspace(0, len(trajectory.q) - 1, frames).round().astype(int)
    return [trajectory.q[i] for i in picks]
