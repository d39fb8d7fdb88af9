"""`mechkit.history.result`: the table round trips (DataFrame, Parquet, CSV), failures included."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit import motion
from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_DURATION, motion_law


@pytest.fixture(scope="module")
def two_t1r(load_cached):
    """The 2T1R along its paper's law, reaction determinacy flagged (every column of the table filled)."""
    mech = load_cached("parallel_2t1r")
    return motion.study(
        mech, motion.from_callable(mech, motion_law, np.linspace(0.2, MOTION_DURATION, 12)), determinacy=True
    )


def _assert_same(a: motion.MotionResult, b: motion.MotionResult) -> None:
    for field in ("t", "q", "v", "a", "efforts", "reactions", "axes", "supports"):
        assert np.array_equal(getattr(a, field), getattr(b, field), equal_nan=True), field
    assert (a.determinate is None) == (b.determinate is None)
    if a.determinate is not None:
        assert np.array_equal(a.determinate, b.determinate)
    for field in ("mechanism", "source", "coordinates", "effort_names", "actuated", "joints", "failures"):
        assert getattr(a, field) == getattr(b, field), field


def test_round_trips(two_t1r, tmp_path):
    r = two_t1r
    _assert_same(r, motion.MotionResult.from_dataframe(r.to_dataframe()))
    motion.write_parquet(r, tmp_path / "m.parquet")
    _assert_same(r, motion.read_parquet(tmp_path / "m.parquet"))
    motion.write_csv(r, tmp_path / "m.csv")
    _assert_same(r, motion.read_csv(tmp_path / "m.csv"))


def test_failures_round_trip(load_cached, tmp_path):
    """The 2T1R law's start is singular: skipped as a row of NaN, named, and kept through the files."""
    mech = load_cached("parallel_2t1r")
    r = motion.study(mech, motion.resample(motion.from_scene(mech, "motion_law"), 5), skip_failures=True)
    assert len(r.failures) == 1 and r.failures[0][0] == 0.0 and "singular" in r.failures[0][1]
    assert np.all(np.isnan(r.efforts[0])) and np.all(np.isfinite(r.efforts[1:]))
    motion.write_parquet(r, tmp_path / "m.parquet")
    _assert_same(r, motion.read_parquet(tmp_path / "m.parquet"))
