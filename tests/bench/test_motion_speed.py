"""`mechkit.bench.motion_speed`: the 2T1R motion law's study timed."""

from __future__ import annotations


def test_speed_benchmark_runs():
    """The benchmark's figures exist and are consistent (its timings are printed by tools/motion_speed.py,
    never asserted)."""
    from mechkit.bench.motion_speed import lines, motion_law_speed

    s = motion_law_speed(samples=6, repeats=1)
    assert s.samples == 6 and min(s.study_s, s.kinematics_s, s.dynamics_s, s.raw_constraint_dynamics_s) > 0
    assert lines(s)[-1].startswith("goal: the whole study under 50 ms")
