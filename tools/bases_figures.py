"""Regenerate docs/bases.md's charts and snapshots: the platform held level on a ship, its isolation chart,
the ten-bar deploying in orbit beside the ground test, the gimbal swinging in flight beside the bench.

Each scene's snapshot is its motion drawn as one picture (`mechkit.viz.pages.overlay`: the last pose solid,
earlier ones faded), the base's own root joints included, rendered by headless Chromium.

Usage: python tools/bases_figures.py [--skip-isolation]   (the isolation chart's 14 simulations take minutes)
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import mechkit
from mechkit.bases import with_base
from mechkit.bases.chart import efforts_chart, floating_chart, held_chart, isolation_chart
from mechkit.mechanisms.rocket_gimbal.scenes import in_flight
from mechkit.mechanisms.spherical_2dof.scenes import isolation_points, on_ship
from mechkit.mechanisms.ten_bar.params import MOTORS
from mechkit.mechanisms.ten_bar.scenes import in_orbit
from mechkit.viz.browser import screenshot
from mechkit.viz.pages import overlay

FIGURES = Path(__file__).resolve().parent.parent / "docs" / "figures"
#: The isolation chart's carrier frequencies (Hz) and servo bandwidths (Hz).
FREQUENCIES, BANDWIDTHS = (0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0), (1.0, 4.0)


def snapshot(mech: mechkit.Mechanism, q, name: str, caption: str) -> Path:
    """`docs/figures/<name>.png`: the motion q (samples, nq) as one picture, four earlier poses faded."""
    every = max(1, (len(q) - 1) // 4)
    poses = [row for row in q[::every]] + ([q[-1]] if (len(q) - 1) % every else [])
    with tempfile.TemporaryDirectory() as tmp:
        page = Path(tmp) / f"{name}.html"
        overlay(mech, caption, ghosts=len(poses) - 1, path=page, poses=poses)
        return screenshot(page, FIGURES / f"{name}.png")


def main(argv: list[str]) -> int:
    """Write every chart and snapshot; print each file."""
    platform = mechkit.load("spherical_2dof")
    held = on_ship(platform)
    print(held_chart(held, FIGURES / "bases_spherical_ship.png", "spherical platform held level on a ship"))
    ship = with_base(platform, "moving")  # the mechanism `on_ship` studies
    print(snapshot(ship, held.study.q, "bases_spherical_ship_snapshot", "on a ship"))
    if "--skip-isolation" not in argv:
        points = isolation_points(platform, FREQUENCIES, BANDWIDTHS)
        print(isolation_chart(points, FIGURES / "bases_spherical_isolation.png", "spherical platform isolation"))
    ten_bar = mechkit.load("ten_bar")
    runs = in_orbit(ten_bar)
    path = FIGURES / "bases_ten_bar_orbit.png"
    print(floating_chart(runs["floating"], runs["orbit"], runs["ground"], list(MOTORS), path, "ten-bar in orbit"))
    print(snapshot(runs["floating"], runs["orbit"].motion.q, "bases_ten_bar_orbit_snapshot", "deploying in orbit"))
    gimbal = mechkit.load("rocket_gimbal")
    flight = in_flight(gimbal)
    actuators = list(gimbal.actuated)
    path = FIGURES / "bases_rocket_gimbal_flight.png"
    print(efforts_chart({"bench": flight["bench"], "flight": flight["flight"]}, actuators, path, "gimbal in flight"))
    print(snapshot(flight["moving"], flight["flight"].q, "bases_rocket_gimbal_snapshot", "swinging in flight"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
