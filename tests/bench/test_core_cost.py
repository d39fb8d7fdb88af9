"""`mechkit.bench.core_cost`: the core's calls against raw Pinocchio."""

from __future__ import annotations

import numpy as np

from mechkit.bench import core_cost


def test_core_cost_rows_carry_their_ratios():
    """`mechkit.bench.core_cost` (tools/bench_core.py): every row has a time, and the core calls carry their
    ratio to raw Pinocchio."""
    rows = core_cost.measure("four_bar", 0.005)
    assert "raw: pin.constraintDynamics (mu=1e-9, 20 it)" in [label for label, _, _ in rows]
    for _, us, _ in rows:
        assert np.isfinite(us) and us > 0
    assert sum("ratio to raw constraintDynamics" in comment for _, _, comment in rows) == 4
