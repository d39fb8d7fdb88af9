"""`mechkit.mechanisms.spherical_2dof.bench`: `mechkit bench spherical_2dof` runs every method."""

from __future__ import annotations

from mechkit.mechanisms.spherical_2dof import SPEC


def test_bench_runs_every_method(mech):
    """`mechkit bench spherical_2dof` (the rows of the former tools/spherical_2dof_bench.py): IK eq. (8),
    the paper's FK, Newton FK, the core's closure solver, Pinocchio's inverse dynamics with and without
    the determinacy test and SOC, each timed."""
    from mechkit.bench.run import bench_mechanism

    b = bench_mechanism(mech, quick=True, with_peers=False)
    by = {r.method.name: r for r in b.rows}
    for name in (
        "closure Newton tol=1e-12",
        "constrained RNEA + determinacy",
        "constrained RNEA, no determinacy",
        *(m.label for m in SPEC.bench_methods),
    ):
        assert by[name].outcome == "ok" and by[name].median_s > 0, name
    assert by["IK eq. (8)"].method.quantity == "inverse_kinematics" and by["IK eq. (8)"].error < 1e-10
