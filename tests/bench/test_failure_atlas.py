"""The failure atlas: every method fails with a growing error or a clear exception, never a silent NaN.

The studies the mechanisms declare are tested with them: the five-bar's singularity in
tests/mechanisms/five_bar/test_failure.py, the gimbal's root loss in
tests/mechanisms/rocket_gimbal/test_failure.py."""

from __future__ import annotations

from conftest import assert_failures_named

from mechkit.bench import failure_atlas


def test_proximal_mu_zero_raises_and_kkt_is_exact():
    cases = failure_atlas.proximal_mu(quick=True)
    assert_failures_named(cases)
    for c in cases:
        if c.method.startswith("constraintDynamics") and c.condition == 0.0:
            assert c.outcome == "SingularConfiguration"
        if c.method.startswith("dense KKT") or (c.method.endswith("it=20") and 0 < c.condition <= 1e-3):
            assert c.error < 1e-10, c
    biased = [c for c in cases if c.method.endswith("it=1") and c.condition == 1e-1]
    assert biased and all(c.outcome == "ConstraintViolated" for c in biased)  # far off: refused, never returned


def test_far_starts_land_somewhere_or_say_so():
    cases = failure_atlas.far_starts(quick=True)
    assert_failures_named(cases)
    for method in {c.method for c in cases}:
        assert any(c.method == method and c.outcome == "ok" for c in cases)


def test_unstabilised_integration_drifts_more():
    cases = failure_atlas.integration(quick=True)
    assert_failures_named(cases)
    end = {}
    for c in cases:
        end[c.method] = c.error
    assert end["semi-implicit Euler, no stabilisation"] > 3 * end["semi-implicit Euler, Baumgarte"]
    assert end["RK4, no stabilisation"] < 1e-6 < end["semi-implicit Euler, no stabilisation"]


def test_the_atlas_runs_the_studies_the_mechanisms_declare(tmp_path):
    """The atlas reads the mechanisms' own studies from their specs (no mechanism imported by name):
    its own three, then the five-bar's singularity and the gimbal's root loss; a declared study runs on
    its mechanism and is drawn."""
    found = failure_atlas.studies()
    assert list(found)[:3] == ["proximal_mu", "far_starts", "integration"]
    assert found["singularity"][1] == "five_bar" and found["root_loss"][1] == "rocket_gimbal"
    study, mechanism = found["root_loss"]
    cases = failure_atlas.run(study, mechanism, quick=True)
    assert_failures_named(cases)
    paths = failure_atlas.draw(study, cases, tmp_path)
    assert [p.name for p in paths] == ["bench_atlas_root_loss.png", "bench_atlas_root_loss.svg"]
