"""Smoke tests of the ten-bar tools (short runs; the full ones are `slow`)."""

from __future__ import annotations

import runpy
import sys
from pathlib import Path

import pytest

TOOLS = Path(__file__).resolve().parent.parent / "tools"


def run_tool(name: str, *args: str) -> None:
    argv = sys.argv
    sys.argv = [name, *args]
    try:
        runpy.run_path(str(TOOLS / name), run_name="__main__")
    finally:
        sys.argv = argv


def test_bench_prints_every_route(capsys):
    run_tool("ten_bar_bench.py", "--repeat", "1")
    out = capsys.readouterr().out
    for row in (
        "pin.constraintDynamics",
        "Lagrange first kind",
        "SOC virtual work",
        "dimension reduction",
        "closed form",
    ):
        assert row in out


@pytest.mark.slow
def test_deploy_report_short(capsys):
    run_tool("ten_bar_deploy.py", "--t-end", "0.2", "--samples", "3")
    assert "worst relative difference" in capsys.readouterr().out


@pytest.mark.slow
def test_plots_written(tmp_path):
    run_tool("ten_bar_plots.py", "--t-end", "0.5", "--out", str(tmp_path))
    for name in ("poses", "angles", "torques", "supports", "drift"):
        assert (tmp_path / f"ten_bar_{name}.png").stat().st_size > 10_000
