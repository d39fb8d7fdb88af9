"""Singularity judged against what the closure resolves, and forward dynamics at any model scale.

Calibration: the five-bar with its distal links collinear (prox1 = 2.6 rad, prox2 at the two roots of
|B1 B2| = dist1 + dist2): assembled at a distance d (rad) from the singular input, the passive block's
condition number grows as 1/sqrt(d); the closure solved to 1e-12 resolves it down to d ~ 1e-10.
"""

from __future__ import annotations

import numpy as np
import pytest
from tests_support import DISTANCES, singular_inputs

import mechkit
from mechkit.base.exceptions import ConstraintViolated, InvalidParameters, SingularConfiguration


def test_calibration_distance_to_the_singular_input_against_condition_number(load_cached):
    m = load_cached("five_bar")
    for root, side in singular_inputs(m):
        conds, caught = [], []
        for d in DISTANCES:
            q = m.assemble({"prox1": 2.6, "prox2": root + side * d}, guess=m.home_q)
            conds.append(m.singularity(q))
            try:
                v = m.velocities(q, [1.0, 1.0])
                caught.append(False)
                assert np.isfinite(conds[-1]) and np.max(np.abs(m.closure_jacobian(q) @ v)) < 1e-9 * np.max(np.abs(v))
            except SingularConfiguration:
                caught.append(True)
                with pytest.raises(SingularConfiguration):
                    m.inverse_dynamics(q, np.zeros(4), np.zeros(4))
                v = m.velocities(q, [1.0, 1.0], allow_singular=True)
                assert np.all(np.isfinite(v)) and np.isfinite(conds[-1])
        # caught at the singular input and within 1e-11 rad of it; regular from 1e-10 rad on
        assert caught == [d <= 1e-11 for d in DISTANCES], list(zip(DISTANCES, caught, conds))
        # condition ~ 1/sqrt(d) away from the rounding floor (the collinear pose of the issue: ~6e5-9e5)
        slope = np.polyfit(np.log(DISTANCES[6:]), np.log(conds[6:]), 1)[0]
        assert slope == pytest.approx(-0.5, abs=0.02)
        assert 3e5 < conds[0] < 2e6


@pytest.mark.parametrize("overrides", [{"density": 1e-3}, {"density": 1e30}, "mm", "km"])
def test_forward_dynamics_scales_with_the_model(overrides, load_cached):
    base = load_cached("five_bar")
    lengths = ("ground", "prox1", "dist1", "prox2", "dist2", "width", "thickness")
    if overrides in ("mm", "km"):
        k = 1e-3 if overrides == "mm" else 1e3
        overrides = {n: getattr(base.params, n) * k for n in lengths}
    m = mechkit.load("five_bar", **overrides)
    q = m.home_q
    v = m.velocities(q, [1.0, -0.5])
    kkt = m.forward_dynamics(q, v, np.zeros(4), "kkt").a
    prox = m.forward_dynamics(q, v, np.zeros(4)).a
    J, gamma = m.closure_jacobian(q), m.closure_drift(q, v)
    assert np.max(np.abs(prox - kkt)) < 1e-9 * np.max(np.abs(kkt))
    assert np.max(np.abs(J @ kkt + gamma)) < 1e-10 * np.max(np.abs(J)) * np.max(np.abs(kkt))


def test_too_light_bodies_and_unconverged_results_are_refused(load_cached):
    with pytest.raises(InvalidParameters, match="mass of"):
        mechkit.load("five_bar", density=1e-12)
    m = load_cached("five_bar")
    v = m.velocities(m.home_q, [1.0, -0.5])
    with pytest.raises(ConstraintViolated, match="J a \\+ gamma"):
        m.forward_dynamics(m.home_q, v, np.zeros(4), mu=1e3, max_iter=1)
