"""Smoke tests of the deployable tools (figures and benchmark) on coarse samples."""

from __future__ import annotations


def test_plots_tool_writes_figures_and_matches_the_paper(load_tool, tmp_path):
    worst = load_tool("deployable_plots").main(step=50.0, folder=tmp_path)
    for name in ("drives", "node_F", "node_I_speed", "node_B_rpy", "efforts"):
        assert (tmp_path / f"deployable_{name}.png").stat().st_size > 10_000
    assert worst["node_position"] < 1e-9 and worst["closure_residual"] < 1e-10
    assert worst["node_I_speed"] < 1e-10 and worst["node_B_rpy"] < 1e-9


def test_bench_tool_measures_one_mechanism(load_tool):
    out = load_tool("deployable_bench").measure("tetra_3rr3uru", budget=0.02, steps=3)
    assert out["nv"] == 18 and out["rows"] == 15
    assert all(out[k] > 0 for k in ("closure solve (warm)", "constraintDynamics (proximal)", "constrained RNEA"))
    assert out["|J a + gamma| kkt"] < 1e-9
    assert out["error a kkt"] < 0.1 * out["max |a| (fold)"]
