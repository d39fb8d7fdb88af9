"""`mechkit.mechanisms.tetra_3rr3uru.bench`: `mechkit bench tetra_3rr3uru` along the fold."""

from __future__ import annotations

import numpy as np


def test_bench_measures_the_unit_along_its_fold(load_cached):
    """`mechkit bench tetra_3rr3uru` (the measurements of the former tools/deployable_bench.py): states
    along the paper's fold, 18 coordinates and 15 rows; the fold step, SOC and the core's methods all
    timed; the dense KKT keeps J a + gamma = 0 and its accelerations within 10 % of the fold's (which are
    tiny: the fold is quasi-static)."""
    from mechkit.bench.run import bench_mechanism

    mech = load_cached("tetra_3rr3uru")
    b = bench_mechanism(mech, quick=True, with_peers=False)
    assert b.nv == 18 and b.rows_closure == 15
    by = {r.method.name: r for r in b.rows}
    for name in (
        "closure Newton tol=1e-12",
        "constraintDynamics mu=1e-09 it=20",
        "constrained RNEA, no determinacy",
        *(m.label for m in mech.spec.bench_methods),
    ):
        assert by[name].outcome == "ok" and by[name].median_s > 0, name
    assert all("t" in s.extra for s in b.samples)
    assert by["dense KKT (independent rows)"].error < 0.1
    for s in b.samples:
        a = mech.forward_dynamics(s.q, s.v, s.tau, method="kkt").a
        assert np.abs(mech.closure_jacobian(s.q) @ a + mech.closure_drift(s.q, s.v)).max() < 1e-9
