"""`mechkit.bench.dynamics_speed` (run on demand: -m bench; it prints its figures, nothing here
asserts a time)."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.bench import dynamics_speed


@pytest.mark.bench
def test_dynamics_speed_rows(load_cached):
    result = dynamics_speed.measure(load_cached("four_bar"), budget=0.05, repeats=5)
    labels = {r.label for r in result.rows}
    assert dynamics_speed.RAW in labels and f"batched inverse_dynamics (N={dynamics_speed.BATCH}), determinacy off" in labels
    assert all(np.isfinite(r.us) and r.us > 0 for r in result.rows)
    print("\n".join(dynamics_speed.markdown([result])))
