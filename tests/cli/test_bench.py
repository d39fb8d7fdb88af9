"""`mechkit bench`: the table with peers, the charts and the markdown page."""

from __future__ import annotations

from mechkit.bench import failure_atlas, loadtime
from mechkit.bench.methods import BASELINES
from mechkit.cli import main


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
