"""`mechkit.mechanisms.rocket_gimbal.bench`: `mechkit bench rocket_gimbal` measures every own method."""

from __future__ import annotations

import numpy as np


def test_bench_measures_every_own_method(mech):
    """`mechkit bench rocket_gimbal` runs the paper's FK, Newton FK, the closed-form IK and SOC (the
    timings of the former tools/rocket_gimbal_bench.py): each a finite, positive time."""
    from mechkit.bench.run import bench_mechanism

    b = bench_mechanism(mech, quick=True, with_peers=False)
    own = {r.method.name: r for r in b.rows if r.method.name in {m.label for m in mech.spec.bench_methods}}
    assert set(own) == {m.label for m in mech.spec.bench_methods}
    assert {r.method.quantity for r in own.values()} == {"assembly", "inverse_kinematics", "inverse_dynamics"}
    assert all(r.outcome == "ok" and np.isfinite(r.median_s) and r.median_s > 0 for r in own.values())
