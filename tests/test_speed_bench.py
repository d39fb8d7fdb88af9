"""Benchmarks of issue 13 (run on demand: -m bench): they print their figures; nothing here asserts a time."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.bench import dynamics_speed, ladder


@pytest.mark.bench
def test_dynamics_speed_rows(load_cached):
    result = dynamics_speed.measure(load_cached("four_bar"), budget=0.05, repeats=5)
    labels = {r.label for r in result.rows}
    assert dynamics_speed.RAW in labels and f"batched inverse_dynamics (N={dynamics_speed.BATCH}), determinacy off" in labels
    assert all(np.isfinite(r.us) and r.us > 0 for r in result.rows)
    print("\n".join(dynamics_speed.markdown([result])))


@pytest.mark.bench
def test_ladder_rows():
    points = ladder.run((1, 2, 4, 8), budget=0.02, repeats=3)
    assert all(p.lcaba_error <= 1e-10 for p in points)
    print("\n".join(ladder.markdown(points)))
