"""`mechkit.bench.run`: a mechanism's bench, the spec's own methods measured like the core's, and the
whole bench."""

from __future__ import annotations

import dataclasses

import pytest

import mechkit
from mechkit.base.exceptions import SingularConfiguration
from mechkit.bench import run
from mechkit.bench.methods import BASELINES
from mechkit.catalog.contract import BenchMethod
from mechkit.loading import from_params


def test_spec_bench_methods_measure_a_wrong_method_and_a_raising_one():
    """A spec's bench_methods rows are measured like the core's: a 1 mrad bias shows as 1e-3 error."""

    def biased(m, s):
        return m.assemble(dict(zip(s.input_names, s.inputs)), guess=m.home_q) + 1e-3

    def refuses(m, s):
        raise SingularConfiguration(float("inf"), "test")

    spec = mechkit.get_spec("four_bar")
    spec = dataclasses.replace(
        spec,
        bench_methods=(
            *spec.bench_methods,
            BenchMethod("biased", "assembly", biased),
            BenchMethod("refuses", "inverse_dynamics", refuses),
        ),
    )
    calls = []
    result = run.bench_mechanism(
        from_params(spec, spec.params()), quick=True, with_peers=False, progress=lambda *args: calls.append(args)
    )
    by = {r.method.name: r for r in result.rows}
    assert [c[1:3] for c in calls] == [(k, len(result.rows)) for k in range(1, len(result.rows) + 1)]
    assert by["biased"].error == pytest.approx(1e-3, rel=1e-6)
    assert by["refuses"].outcome.startswith("raises SingularConfiguration")
    # the core against the independent closed form and planar Newton-Euler
    assert by[BASELINES["assembly"]].error < 1e-10
    assert by[BASELINES["forward_dynamics"]].error < 1e-9
    assert by[BASELINES["inverse_dynamics"]].error < 1e-9
    assert by["dense KKT (independent rows)"].error < 1e-9
    assert by["Lagrange first kind (numpy, from link motion)"].error < 1e-9
    assert by["Lagrange first kind, forward (numpy, from link motion)"].error < 1e-9
    soc = by["sequential SOC virtual work (numpy, from link motion)"]
    assert soc.error < 1e-9 and soc.note == ""  # every pin's in-plane force compared
    # one proximal iteration at a large mu is biased: the result violates J a + gamma = 0 and is refused
    assert by["constraintDynamics mu=0.001 it=1"].outcome.startswith("raises ConstraintViolated")


def test_a_sprung_mechanism_is_benched_rigid(load_cached):
    """The ten-bar has an R5 spring-damper; the bench measures it without (`rigid_mechanism`), as its
    Lagrange references, the raw Pinocchio call and the peers take it: the core agrees with them to round-off
    (with the spring, the forward dynamics differed by 9.6 rad/s^2 and the efforts by 1.6 N m)."""
    result = run.bench_mechanism(load_cached("ten_bar"), quick=True, with_peers=False)
    by = {r.method.name: r for r in result.rows}
    assert not result.mech.springs and load_cached("ten_bar").springs
    for name in (BASELINES["forward_dynamics"], "dense KKT (independent rows)", "raw pin.constraintDynamics (mu=1e-9)"):
        assert by[name].error < 1e-9, name
    assert by[BASELINES["inverse_dynamics"]].error < 1e-9


@pytest.mark.bench
def test_full_bench_measures_every_registered_mechanism():
    results, skipped = run.run(quick=True)
    assert not skipped, skipped
    assert {b.name for b in results} == set(mechkit.specs())
    for b in results:
        by = {r.method.name: r for r in b.rows}
        for name in BASELINES.values():
            assert by[name].outcome == "ok" or by[name].outcome.startswith("raises"), (b.name, name)
