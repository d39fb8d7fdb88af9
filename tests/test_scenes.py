"""`mechkit.scenes`: the scenes a spec declares and the generic input sweep, their poses checked; scene times."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from mechkit import motion, scenes
from mechkit.base.exceptions import InvalidParameters, MalformedDescription
from mechkit.loading import from_params
from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_DURATION, MOTION_RATES
from mechkit.scenes import scene_times


def test_sweep_moves_each_input_in_turn_and_stays_assembled(load_cached):
    m = load_cached("five_bar")
    poses = scenes.sweep(m, frames=12)
    assert len(poses) == 1 + 12 * len(m.actuated)
    assert np.array_equal(poses[0], m.home_q)
    home = np.array([m.home_q[m.q_index(j)] for j in m.actuated])
    for n, q in enumerate(poses[1:]):
        i, t = divmod(n, 12)
        expected = home.copy()
        expected[i] += scenes.SWEEP_ANGLE * math.sin(2 * math.pi * (t + 1) / 12)
        assert np.allclose([q[m.q_index(j)] for j in m.actuated], expected, atol=1e-12)
        assert np.max(np.abs(m.closure_residual(q))) < 1e-10
    steps = np.abs(np.diff(poses, axis=0)).max()
    assert steps < 3 * scenes.SWEEP_ANGLE * 2 * math.pi / 12  # continuous: no jump to another assembly branch
    assert np.allclose(poses[-1], m.home_q, atol=1e-9)


def test_sweep_stops_at_the_first_pose_that_does_not_assemble(load_cached):
    m = load_cached("five_bar")
    with pytest.warns(scenes.SweepStopped, match=r"sweep of prox1 stops at .* do not assemble"):
        poses = scenes.sweep(m, frames=24, angle=3.0)
    assert 2 <= len(poses) < 1 + 24 * 2
    assert all(np.max(np.abs(m.closure_residual(q))) < 1e-10 for q in poses)
    assert np.allclose(poses[-1], m.home_q)  # each excursion comes back home


def test_scene_protocol(load_cached):
    """The scenes a spec declares come first, in order, then the generic sweep; their poses are checked."""
    four_bar = load_cached("four_bar")
    good = [four_bar.assemble([a]) for a in np.linspace(0.5, 0.9, 5)]
    bad = [good[0], good[1] + 0.1]
    spec = dataclasses.replace(
        four_bar.spec, scenes={"turn": lambda mech: good, "bad": lambda mech: bad, "short": lambda mech: good[:1]}
    )
    m = from_params(spec, four_bar.params)
    assert list(scenes.scenes(m)) == ["turn", "bad", "short", "sweep"]
    assert all(np.array_equal(a, b) for a, b in zip(scenes.scene_poses(m, "turn"), good))
    with pytest.raises(MalformedDescription, match="pose 1 does not close its loops"):
        scenes.scene_poses(m, "bad")
    with pytest.raises(MalformedDescription, match="at least 2 poses"):
        scenes.scene_poses(m, "short")
    with pytest.raises(InvalidParameters, match="turn, bad, short, sweep"):
        scenes.scene_poses(m, "dance")


def crank_law(t: float):
    """Four-bar crank: a smooth swing (rad, rad/s, rad/s^2)."""
    w = 2.0
    return (
        np.array([0.6 + 0.3 * np.sin(w * t)]),
        np.array([0.3 * w * np.cos(w * t)]),
        np.array([-0.3 * w * w * np.sin(w * t)]),
    )


@pytest.fixture(scope="module")
def four_bar(load_cached):
    mech = load_cached("four_bar")
    return mech, motion.study(mech, motion.from_callable(mech, crank_law, np.linspace(0.0, 3.0, 16)))


def test_scene_time_axis(load_cached):
    mech = load_cached("parallel_2t1r")
    assert np.allclose(scene_times(mech, "motion_law", 101), np.linspace(0.0, MOTION_DURATION, 101))
    law = motion.from_scene(mech, "motion_law")
    assert np.allclose(law.rates, MOTION_RATES, atol=1e-9)  # linear inputs: the spline is exact
    assert np.array_equal(scene_times(load_cached("four_bar"), "sweep", 3), [0.0, 1.0, 2.0])
