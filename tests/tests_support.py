"""Shared helpers of the tests (not tests themselves): the five-bar's singular inputs."""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

#: Distances (rad) from the five-bar's collinear input at which the singularity tests look.
DISTANCES = (0.0, 1e-14, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-6, 1e-4, 1e-2)


def singular_inputs(m) -> list[tuple[float, float]]:
    """prox2 angles (rad) where the five-bar's distal links are collinear at prox1 = 2.6, and the side
    (+1, -1) from which the assembly approaches each."""
    p = m.params
    b1 = p.prox1 * np.array([np.cos(2.6), np.sin(2.6)])

    def gap(t):
        return np.linalg.norm(np.array([p.ground + p.prox2 * np.cos(t), p.prox2 * np.sin(t)]) - b1) - (p.dist1 + p.dist2)

    return [(brentq(gap, -1.5, -0.5, xtol=1e-16), -1.0), (brentq(gap, 0.5, 1.0, xtol=1e-16), 1.0)]
