"""`mechkit.mechanisms.ten_bar.bench`: `mechkit bench ten_bar` runs every route."""

from __future__ import annotations


def test_bench_runs_every_route(mech):
    """`mechkit bench ten_bar` (the routes of the former tools/ten_bar_bench.py): constrained ABA
    (pin.constraintDynamics), the Lagrange first kind forward and inverse, SOC virtual work, the
    dimension reduction and the closed form, each timed and agreeing with the references."""
    from mechkit.bench.run import bench_mechanism

    b = bench_mechanism(mech, quick=True, with_peers=False)
    by = {r.method.name: r for r in b.rows}
    for name in (
        "raw pin.constraintDynamics (mu=1e-9)",
        "constrained RNEA, no determinacy",
        *(m.label for m in mech.spec.bench_methods),
    ):
        assert by[name].outcome == "ok" and by[name].median_s > 0, name
    for m in mech.spec.bench_methods:
        assert by[m.label].error < 1e-9, m.label
    assert {m.quantity for m in mech.spec.bench_methods} == {"assembly", "forward_dynamics", "inverse_dynamics"}
