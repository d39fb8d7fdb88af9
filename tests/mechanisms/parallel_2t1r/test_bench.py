"""`mechkit.mechanisms.parallel_2t1r.bench`: `mechkit bench parallel_2t1r` runs every method."""

from __future__ import annotations


def test_bench_runs_every_method(mech):
    """`mechkit bench parallel_2t1r` (the rows of the former tools/parallel_2t1r_bench.py): Pinocchio's
    constrained RNEA with and without the determinacy test, SOC, classic virtual work and the paper's
    position analysis, each timed, SOC and classic agreeing with the reference."""
    from mechkit.bench.run import bench_mechanism

    b = bench_mechanism(mech, quick=True, with_peers=False)
    by = {r.method.name: r for r in b.rows}
    for name in (
        "constrained RNEA + determinacy",
        "constrained RNEA, no determinacy",
        "SOC, 3 SKCs (numpy, from the analytic state)",
        "classic virtual work (numpy, from the analytic state)",
        "paper FK (eqs. 7-9) + closed-form joints",
    ):
        assert by[name].outcome == "ok" and by[name].median_s > 0 and by[name].error < 1e-9, name
    assert by["classic virtual work (numpy, from the analytic state)"].note == "efforts only"
