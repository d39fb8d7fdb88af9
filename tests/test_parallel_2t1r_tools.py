"""Smoke tests of the 2T1R tools (figures and benchmark), on few samples."""

from __future__ import annotations


def test_plots_write_both_figures(tmp_path, load_tool):
    assert load_tool("parallel_2t1r_plots").main(["--samples", "10", "--out", str(tmp_path)]) == 0
    for name in ("comparison", "singular"):
        png = tmp_path / f"parallel_2t1r_{name}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000


def test_bench_prints_every_method(capsys, load_tool):
    assert load_tool("parallel_2t1r_bench").main(["--samples", "3", "--repeat", "1"]) == 0
    out = capsys.readouterr().out
    for row in ("Pinocchio constrained RNEA", "SOC", "classic virtual work", "analytic motion state"):
        assert row in out
