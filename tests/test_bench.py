"""mechkit bench: error measurement, ratios, the spec's bench methods, first load, and a quick smoke run."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import mechkit
from mechkit.base.exceptions import SingularConfiguration
from mechkit.bench import core_cost, errors, failure_atlas, loadtime, run, timing
from mechkit.bench.methods import BASELINES, Method, own_methods, references
from mechkit.bench.results import Row
from mechkit.bench.sampling import make_samples
from mechkit.catalog.contract import BenchMethod
from mechkit.catalog.registry import names
from mechkit.cli import main
from mechkit.loading import from_params


def _row(name: str, quantity: str, seconds: float, error: float) -> Row:
    return Row("m", Method(name, quantity, lambda m, s: None), median_s=seconds, error=error)


def test_ratio_to_fastest_of_equal_or_better_accuracy():
    rows = [_row("slow exact", "forward_dynamics", 10e-6, 1e-15), _row("fast exact", "forward_dynamics", 2e-6, 1e-13),
            _row("fastest sloppy", "forward_dynamics", 1e-6, 1e-2),
            _row(BASELINES["forward_dynamics"], "forward_dynamics", 4e-6, 1e-14)]
    timing.ratios(rows)
    by = {r.method.name: r for r in rows}
    assert by["slow exact"].x_fastest == pytest.approx(5.0)  # both exact within the machine-precision class
    assert by["fast exact"].x_fastest == pytest.approx(1.0)
    assert by["fastest sloppy"].x_fastest == pytest.approx(1.0)  # nothing as fast is as sloppy or better... itself
    assert by["slow exact"].x_base == pytest.approx(2.5)


def test_efforts_only_is_no_yardstick_for_reactions():
    full = _row("with reactions", "inverse_dynamics", 10e-6, 1e-15)
    cheap = _row("efforts only", "inverse_dynamics", 1e-6, 1e-15)
    cheap.note = "efforts only"
    timing.ratios([full, cheap])
    assert full.x_fastest == pytest.approx(1.0) and cheap.x_fastest == pytest.approx(1.0)


def test_inverse_error_compares_determinate_components_only():
    ref = errors.IDReference({"m1": 2.0}, {"j": np.array([1.0, 5.0, 0, 0, 0, 0]), "m1": np.array([0, 0, 1.0, 0, -2.0, 0])},
                            {"j": np.array([True, False, True, True, True, True]), "m1": np.ones(6, bool)})
    good = {"efforts": {"m1": 2.0}, "reactions": {"j": np.array([1.0, -99.0, 0, 0, 0, 0]), "m1": np.array([0, 0, 1.0, 0, 7.0, 0])}}
    err, note = errors.inverse_error(good, ref, ("m1",))
    assert err == 0.0 and note == ""  # the indeterminate fy and the actuated joint's moment are not compared
    bad = {"efforts": {"m1": 2.5}}
    err, note = errors.inverse_error(bad, ref, ("m1",))
    assert err == pytest.approx(0.5 / 5.0) and note == "efforts only"


def test_time_per_call_counts_every_call():
    calls = []
    times = timing.time_per_call(lambda s: calls.append(s), [1, 2], budget_s=0.01, repeats=3)
    assert times.shape == (3,) and np.all(times > 0)
    assert set(calls) == {1, 2}


def test_spec_bench_methods_measure_a_wrong_method_and_a_raising_one():
    """A spec's bench_methods rows are measured like the core's: a 1 mrad bias shows as 1e-3 error."""
    def biased(m, s):
        return m.assemble(dict(zip(s.input_names, s.inputs)), guess=m.home_q) + 1e-3

    def refuses(m, s):
        raise SingularConfiguration(float("inf"), "test")

    spec = mechkit.get_spec("four_bar")
    spec = dataclasses.replace(spec, bench_methods=(*spec.bench_methods, BenchMethod("biased", "assembly", biased),
                                                    BenchMethod("refuses", "inverse_dynamics", refuses)))
    calls = []
    result = run.bench_mechanism(from_params(spec, spec.params()), quick=True, with_peers=False,
                                 progress=lambda *args: calls.append(args))
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


def test_quick_bench_smoke(tmp_path, capsys, monkeypatch):
    """`mechkit bench four_bar --quick` prints the table with peers, writes charts and the markdown."""
    # the atlas studies and the first load have their own tests: keep one study here to check the
    # wiring, and the run short
    proximal = next(study for study in failure_atlas.OWN if study.name == "proximal_mu")
    monkeypatch.setattr(failure_atlas, "studies", lambda: {"proximal_mu": (proximal, None)})
    first_load = loadtime.first_load
    monkeypatch.setattr(loadtime, "first_load", lambda runs: first_load(runs=1))
    md = tmp_path / "bench.md"
    assert main(["bench", "four_bar", "--quick", "--charts", str(tmp_path), "--markdown", str(md)]) == 0
    out = capsys.readouterr().out
    assert "us/call" in out and "x fastest" in out
    for quantity in BASELINES:  # the quantities the core computes (inverse kinematics: the mechanisms' own only)
        assert quantity in out
        for ext in ("png", "svg"):
            assert (tmp_path / f"bench_four_bar_{quantity}.{ext}").stat().st_size > 1000
    assert "[peer] MuJoCo mj_forward (default solref/solimp)" in out
    text = md.read_text()
    assert "## Machine" in text and "pinocchio" in text and "## Goals" in text and "## Failure atlas" in text
    assert "## First load" in text and "mechkit.mechanisms.four_bar" in text
    assert (tmp_path / "bench_atlas_proximal_mu.png").exists() and "bench_atlas_proximal_mu.png" in text


@pytest.mark.bench
def test_full_bench_measures_every_registered_mechanism():
    results, skipped = run.run(quick=True)
    assert not skipped, skipped
    assert {b.name for b in results} == set(mechkit.specs())
    for b in results:
        by = {r.method.name: r for r in b.rows}
        for name in BASELINES.values():
            assert by[name].outcome == "ok" or by[name].outcome.startswith("raises"), (b.name, name)


def test_core_cost_rows_carry_their_ratios():
    """`mechkit.bench.core_cost` (tools/bench_core.py): every row has a time, and the core calls carry their
    ratio to raw Pinocchio."""
    rows = core_cost.measure("four_bar", 0.005)
    assert "raw: pin.constraintDynamics (mu=1e-9, 20 it)" in [label for label, _, _ in rows]
    for _, us, _ in rows:
        assert np.isfinite(us) and us > 0
    assert sum("ratio to raw constraintDynamics" in comment for _, _, comment in rows) == 4


#: Largest error of a mechanism's own method against the bench's reference, per quantity (rad or m;
#: relative for dynamics). The trusses' fold is quasi-static (|a| ~ 1e-6 rad/s^2): none of their own
#: methods is a forward dynamics.
AGREEMENT = {"assembly": 1e-9, "inverse_kinematics": 1e-9, "forward_dynamics": 1e-8, "inverse_dynamics": 1e-8}


@pytest.mark.parametrize("name", names())
def test_every_declared_bench_method_agrees_with_the_reference(name, load_cached):
    """Each mechanism's own methods (the papers' closed forms, SOC, Lagrange) run on the bench's states
    and agree with the reference of their quantity (the spec's own where it declares one, else the core's)."""
    mech = load_cached(name)
    samples = make_samples(mech, 2)
    refs = references(mech, samples)
    for method in own_methods(mech):
        row = timing.measure(mech, method, samples, refs, budget_s=1e-4, repeats=1)
        assert row.outcome == "ok", (name, method.name, row.outcome)
        assert row.error < AGREEMENT[method.quantity], (name, method.name, row.error)


def test_first_load_times_a_fresh_process_and_lists_its_mechanism_modules():
    """Not a timing test: the measurement returns positive times and the imported modules (four_bar's only)."""
    first = loadtime.first_load("four_bar", runs=1)
    assert len(first.process_s) == len(first.inside_s) == 1
    assert 0 < first.inside_s[0] < first.process_s[0]
    assert "mechkit.mechanisms.four_bar" in first.modules
    assert first.others == ()
