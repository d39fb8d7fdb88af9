"""The passive solve (`mechkit.core.passive_solve`): a passive block that does not determine the free
coordinates is refused, in a batch as in one sample, unless asked for; idle freedoms take their
minimum-norm value."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

import mechkit
from mechkit.base.exceptions import SingularConfiguration

FIXTURES = Path(__file__).resolve().parent.parent / "fixtures"


def test_batched_singular_sample_raises_and_allow_singular_passes(load_cached):
    """Five-bar 1e-12 rad from its collinear input (tests/test_bad_inputs_singular.py) beside a regular
    sample: the batch raises as the single call does; with `allow_singular` both equal their single calls."""
    m = load_cached("five_bar")
    p = m.params
    b1 = p.prox1 * np.array([np.cos(2.6), np.sin(2.6)])

    def gap(t):
        return np.linalg.norm(np.array([p.ground + p.prox2 * np.cos(t), p.prox2 * np.sin(t)]) - b1) - (
            p.dist1 + p.dist2
        )

    root = brentq(gap, 0.5, 1.0, xtol=1e-16)
    Q = np.array([m.home_q, m.assemble({"prox1": 2.6, "prox2": root + 1e-12}, guess=m.home_q)])
    rates = np.ones((2, 2))
    with pytest.raises(SingularConfiguration):
        m.velocities(Q[1], rates[1])
    with pytest.raises(SingularConfiguration):
        m.velocities_batch(Q, rates)
    V = m.velocities_batch(Q, rates, allow_singular=True)
    for i in range(2):
        v = m.velocities(Q[i], rates[i], allow_singular=True)
        assert np.abs(V[i] - v).max() <= 1e-13 * np.abs(v).max()
    assert m.singularity(Q[1]) > 1e5


def test_under_determined_inputs_are_refused(load_cached):
    m = load_cached("five_bar")
    with pytest.raises(SingularConfiguration):
        m.velocities(m.home_q, [1.0], inputs=["prox1"])


def test_idle_spins_take_their_minimum_norm_rates():
    """With the two motors given, the rods' spins are idle freedoms: the velocities get the
    minimum-norm spin rates (orthogonal to each spin), every other joint the rates the motors fix, and
    adding a spin changes no other joint's rate."""
    m = mechkit.load(FIXTURES / "leg.urdf")
    J = m.closure_jacobian(m.home_q)
    motors_only = m.velocities(m.home_q, [1.0, -0.5])
    assert np.max(np.abs(J @ motors_only)) < 1e-12
    for rod in ("rod1_top_z", "rod2_top_z"):  # each rod is vertical at q = 0: its spin is its ball's z rate
        spin = np.zeros(m.model.nv)
        spin[m.v_index(rod) + 2] = 1.0
        assert np.max(np.abs(J @ spin)) < 1e-15
        assert abs(spin @ motors_only) <= 1e-12 * np.linalg.norm(motors_only)
        spun = motors_only + 3.0 * spin
        for joint in ("knee", "ankle", "hip", "knee_motor"):
            assert spun[m.v_index(joint)] == motors_only[m.v_index(joint)]
