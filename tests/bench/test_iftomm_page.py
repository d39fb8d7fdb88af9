"""`mechkit.bench.iftomm_page`: the problems' rows (errors against their references, the criterion) and
the page's table."""

from __future__ import annotations

import pytest

from mechkit.bench import iftomm, iftomm_page


def test_the_pendulum_row_meets_high_precision_and_mujoco_runs():
    """2 s of the pendulum: error against the exact solution < 1e-6 m (measured 1e-7 over 10 s), MuJoCo's
    cell a measured error."""
    pytest.importorskip("mujoco")
    row = iftomm_page.run_pendulum(2.0)
    assert row.error < 1e-6 and row.passed and row.mujoco.endswith("steps)")


def test_the_table_says_met_and_missed():
    rows = [
        iftomm.Row("a", 1e-7, "ref", 0.1, 10, "m", "p"),
        iftomm.Row("b", 2e-3, "ref", 0.1, 10, "m", "p"),
    ]
    lines = iftomm_page.table(rows).splitlines()
    assert "| met |" in lines[2] and "| missed |" in lines[3] and len(lines) == 4


def test_the_flyball_row_has_mujoco_unstable_at_1_ms_and_agreeing_at_0_1_ms():
    """The stiff springs as MuJoCo tendons: RK4 at 1 ms diverges (MuJoCo's instability warning), RK4 at 0.1 ms
    follows the Pinocchio reference to 1e-8 m (measured 5.8e-10 m), as mechkit's RK45 does (1e-8 m)."""
    pytest.importorskip("mujoco")
    row = iftomm_page.run_flyball(0.05, method="RK45", rtol=1e-8)
    cells = row.mujoco.split("; ")
    assert row.error < 1e-8 and "unstable" in cells[0]
    assert float(cells[1].split(": ")[1].split(" m")[0]) < 1e-8
