"""`mechkit.validation.planar_newton_euler`: the planar linkages' global force, moment and power
balance; the reactions' format."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.validation.planar_motion import LinkageState
from mechkit.validation.planar_newton_euler import newton_euler

from .planar_laws import TIMES, G, five_bar_at, four_bar_at


def _balance_residuals(s: LinkageState) -> tuple[float, float, float]:
    """Whole-linkage force, moment (about the origin) and power balance, relative to their scale."""
    links = s.links.values()
    ground = [j for j in s.joints if j.parent is None]
    dyn = newton_euler(s, G)
    g2 = G[[0, 2]]
    force = sum(dyn.reactions[j.name][[0, 2]] for j in ground) + sum(link.bar.mass * g2 for link in links)
    inertial = sum(link.bar.mass * link.com_acceleration for link in links)

    def cross(a: np.ndarray, b: np.ndarray) -> float:
        return float(a[0] * b[1] - a[1] * b[0])

    moment = sum(cross(j.point, dyn.reactions[j.name][[0, 2]]) for j in ground)
    moment += sum(cross(link.com, link.bar.mass * g2) for link in links) + sum(dyn.efforts.values())
    d_angular = sum(
        cross(link.com, link.bar.mass * link.com_acceleration) + link.bar.inertia_planar * link.alpha for link in links
    )
    power_in = sum(u * s.qd[s.coordinates.index(j)] for j, u in dyn.efforts.items())
    power_in += sum(link.bar.mass * g2 @ link.com_velocity for link in links)
    d_energy = sum(
        link.bar.mass * link.com_acceleration @ link.com_velocity + link.bar.inertia_planar * link.alpha * link.omega
        for link in links
    )
    scale = max(np.abs(np.concatenate([*dyn.reactions.values(), list(dyn.efforts.values())])))
    return (
        float(np.max(np.abs(force - inertial))) / scale,
        abs(moment - d_angular) / scale,
        abs(power_in - d_energy) / scale,
    )


@pytest.mark.parametrize("build", [four_bar_at, five_bar_at])
def test_newton_euler_global_balance(build) -> None:
    for t in TIMES:
        assert max(_balance_residuals(build(t))) < 1e-12


def test_newton_euler_reaction_format() -> None:
    s = five_bar_at(0.3)
    dyn = newton_euler(s, G)
    assert set(dyn.reactions) == {"prox1", "dist1", "prox2", "dist2", "C"}
    for name, w in dyn.reactions.items():
        assert w.shape == (6,) and w[1] == w[3] == w[5] == 0.0
        assert w[4] == (-dyn.efforts[name] if name in dyn.efforts else 0.0)
