"""Input laws the motion tests share."""

from __future__ import annotations

import numpy as np


def crank_law(t: float):
    """Four-bar crank: a smooth swing (rad, rad/s, rad/s^2)."""
    w = 2.0
    return (
        np.array([0.6 + 0.3 * np.sin(w * t)]),
        np.array([0.3 * w * np.cos(w * t)]),
        np.array([-0.3 * w * w * np.sin(w * t)]),
    )
