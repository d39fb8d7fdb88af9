"""The base studies' charts are written (PNG), from short real runs."""

from __future__ import annotations

import numpy as np

from mechkit.bases import base_motion, held_motion, with_base
from mechkit.bases.chart import efforts_chart, floating_chart, held_chart, isolation_chart
from mechkit.bases.isolation import IsolationPoint, servo_theory

PNG = b"\x89PNG"


def test_isolation_chart(tmp_path):
    points = [
        IsolationPoint(f, b, servo_theory(f, b), servo_theory(f, b), 0.0) for b in (1.0, 4.0) for f in (0.1, 1, 10)
    ]
    assert isolation_chart(points, tmp_path / "iso.png").read_bytes()[:4] == PNG


def test_held_and_floating_charts(load_cached, tmp_path):
    grounded = load_cached("spherical_2dof")
    moving = with_base(grounded, "moving")
    motion = base_motion.from_callable(lambda t: np.r_[0, 0, 0, 0.1 * np.sin(t), 0, 0], np.linspace(0, 1, 6))
    held = held_motion(moving, motion, "platform", ((0, 0, 1), (0, 0, 1)))
    assert held_chart(held, tmp_path / "held.png").read_bytes()[:4] == PNG
    path = efforts_chart({"carried": held.study}, ["r11", "r21"], tmp_path / "efforts.png")
    assert path.read_bytes()[:4] == PNG
    floating = with_base(grounded, "floating", base_inertia=(5.0, (0.1, 0.1, 0.1)), gravity=(0, 0, 0))
    home = grounded.spec.home(grounded.params)

    def law(t):
        return np.array([home["r11"] + 0.1 * t, home["r21"]]), np.array([0.1, 0.0]), np.zeros(2)

    runs = [m.simulate(0.2, inputs=law, input_names=["r11", "r21"], dynamics="kkt") for m in (floating, grounded)]
    path = floating_chart(floating, *runs, ["r11", "r21"], tmp_path / "floating.png")
    assert path.read_bytes()[:4] == PNG
