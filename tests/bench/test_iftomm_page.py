"""`mechkit.bench.iftomm_page`: the problems' rows (errors against their references, the criterion) and
the page's table."""

from __future__ import annotations

import pytest

from mechkit.base.exceptions import InvalidArgument
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


def test_the_flyball_s_radau_row_follows_the_reference():
    """Radau (the analytic Jacobian) over 0.05 s of the transient at rtol 1e-8: s within 1e-8 m of the reference;
    its MuJoCo cell points to the RK45 row's."""
    row = iftomm_page.run_flyball(0.05, method="Radau", rtol=1e-8, mujoco=False)
    assert row.error < 1e-8 and row.mujoco == "as in the RK45 row" and "Radau" in row.problem


def test_only_some_problems_are_measured_again_and_the_other_rows_kept(tmp_path, monkeypatch):
    """`write_page(only=["flyball"])` replaces the flyball's rows and keeps the others as the page had them,
    in the page's order; an unknown problem is refused by name."""
    page = tmp_path / "iftomm_benchmarks.md"
    old = [iftomm.Row(f"{start} old", 1e-7, "ref", 1.0, 10, "m", "p") for start, _ in iftomm_page.PROBLEMS.values()]
    before = "## Problems\n\n| problem |\n|---|\n| simple pendulum, defined |\n| Bricard's, defined |\n\n"
    page.write_text(f"# t\n\n{before}{iftomm_page.HEADING}\n\n{iftomm_page.table(old)}\n\n## After\n\nkept\n")
    new = [
        iftomm.Row("flyball governor, new A", 2e-3, "ref", 2.0, 20, "m", "p"),
        iftomm.Row("flyball governor, new B", 1e-9, "ref", 3.0, 30, "m", "p"),
    ]
    monkeypatch.setitem(iftomm_page.PROBLEMS, "flyball", ("flyball governor", lambda: new))
    assert iftomm_page.write_page(tmp_path, only=["flyball"]) == new
    text = page.read_text()
    rows = [
        line.split(" | ")[0] for line in text.splitlines() if line.startswith("| ") and ("old" in line or "new" in line)
    ]
    assert rows == ["| simple pendulum old", "| N-four-bar N = 2, old", "| Bricard old", "| flyball governor, new A",
                    "| flyball governor, new B", "| N-four-bar N = 40, old"]  # fmt: skip
    assert "| missed |" in text and text.endswith("## After\n\nkept\n") and text.count("defined |") == 2
    with pytest.raises(InvalidArgument, match="only"):
        iftomm_page.write_page(tmp_path, only=["flyballs"])
