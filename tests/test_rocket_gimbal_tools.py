"""Smoke tests of the engine gimbal's tools (small grids; figures written to a temporary folder)."""

from __future__ import annotations

import numpy as np


def test_linearisation_tool_writes_its_figure_and_reports_the_worst_error(tmp_path, load_tool):
    out = tmp_path / "lin.png"
    result = load_tool("rocket_gimbal_linearisation").main(n=5, out=out)
    assert out.stat().st_size > 10_000
    # on a 5 x 5 grid the corners are included: the worst error sits at a corner
    assert 0.4 < result["worst_deg"] < 0.6 and abs(result["worst_at_mm"][0]) == 110.0
    assert np.isclose(result["worst_percent"], 100 * result["worst_deg"] / 6.5)


def test_resultant_tool_runs(tmp_path, capsys, load_tool):
    tool = load_tool("rocket_gimbal_resultant")
    from mechkit.mechanisms.rocket_gimbal.params import RocketGimbalParams, geometry

    geo = geometry(RocketGimbalParams())
    tool.example(geo)
    tool.grid_map(geo, 5, tmp_path / "cond.png")
    text = capsys.readouterr().out
    assert "in-range pick" in text and "double root" in text
    assert (tmp_path / "cond.png").stat().st_size > 10_000


def test_bench_tool_runs(tmp_path, load_tool):
    result = load_tool("rocket_gimbal_bench").main(budget_s=0.05, out=tmp_path / "bench.png")
    assert all(np.isfinite(v) and v > 0 for v in result.values())
    assert (tmp_path / "bench.png").stat().st_size > 5_000


def test_swing_tool_compares_pinocchio_and_soc(tmp_path, load_tool):
    result = load_tool("rocket_gimbal_swing").main(n=6, out=tmp_path / "swing.png")
    assert result["worst relative difference Pinocchio vs SOC"] < 1e-8
    assert 1.1 < result["bearing force max (MN)"] < 1.3  # the 1.2 MN thrust plus weight and inertia
    assert (tmp_path / "swing.png").stat().st_size > 10_000
