"""The planar four-bar and five-bar along smooth input laws (closed form), at the instants the tests use."""

from __future__ import annotations

import numpy as np

from mechkit.validation.planar_closed_form import five_bar, four_bar
from mechkit.validation.planar_motion import LinkageState

G = np.array([0.0, 0.0, -9.81])
TIMES = np.linspace(0.0, 1.0, 9)


def law(t: float, mean: float, phase: float) -> tuple[float, float, float]:
    """Smooth input law (angle, rate, acceleration): mean + 2 pi t / 3 + 0.3 sin(2 pi t + phase)."""
    w = 2.0 * np.pi
    return (
        mean + w * t / 3 + 0.3 * np.sin(w * t + phase),
        w / 3 + 0.3 * w * np.cos(w * t + phase),
        -0.3 * w**2 * np.sin(w * t + phase),
    )


def four_bar_at(t: float, elbow_up: bool = True) -> LinkageState:
    return four_bar(*law(t, 0.3, 0.0), elbow_up=elbow_up)


def five_bar_at(t: float, elbow_up: bool = True) -> LinkageState:
    (a1, r1, c1), (a2, r2, c2) = law(t, 1.7, 0.0), law(t, 1.0, 1.3)
    return five_bar((a1, a2), (r1, r2), (c1, c2), elbow_up=elbow_up)
