"""What the export tests share: the mechanisms exported and read back, and a pose away from home."""

from __future__ import annotations

import numpy as np

#: Mechanisms whose exports are read back by MuJoCo and Pinocchio (a planar, a spatial and two
#: spherical-cut linkages).
NAMES = ["four_bar", "five_bar", "rocket_gimbal", "spherical_2dof"]


def other_pose(m) -> np.ndarray:
    """An assembled configuration away from home (the one the MJCF is written at)."""
    home = np.array([m.home_q[m.q_index(j)] for j in m.actuated])
    return m.assemble(home + 0.02, guess=m.home_q)
