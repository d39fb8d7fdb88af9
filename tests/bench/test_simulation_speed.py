"""`mechkit.bench.simulation_speed`: the simulator against MuJoCo on the exported MJCF at the same step (the
motions agree, each side's closure error), and the benchmark page's section written in place."""

from __future__ import annotations

import pytest

from mechkit.bench.simulation_speed import HEADING, SimulationSpeed, markdown, write_section


@pytest.fixture(scope="module")
def four_bar(load_cached):
    return load_cached("four_bar")


def test_against_mujoco_on_the_exported_mjcf(four_bar):
    """The same free motion in MuJoCo (exported MJCF, stiff equality settings, its RK4 at its step) and in
    the simulator at that step (RK45 and RK4): the joint values agree to 1e-6 rad over 0.3 s (measured 4e-8), MuJoCo's
    loop opening by its soft constraint (measured 7e-9 m) and ours held to round-off."""
    pytest.importorskip("mujoco")
    from mechkit.bench.simulation_speed import simulation_speed

    for method in ("RK45", "RK4"):  # RK4 is MuJoCo's own method: the same order at the same step
        row = simulation_speed(four_bar, 0.3, method)
        assert row.difference < 1e-6 and row.method == method and row.mujoco_method == "RK4"
        # ours within the projection's drift tolerance (1e-11 m), far below MuJoCo's soft closure
        assert row.mechkit_closure <= 1e-11 < row.mujoco_closure < 1e-4


def test_semi_implicit_euler_against_mujocos_euler(four_bar):
    """Both first order at the same step (MuJoCo's Euler is semi-implicit): over 0.3 s the joint values agree
    to the first-order error of either (measured 2e-4 rad), ours closed to 1e-11 m."""
    pytest.importorskip("mujoco")
    from mechkit.bench.simulation_speed import simulation_speed

    row = simulation_speed(four_bar, 0.3, "SymplecticEuler")
    assert row.mujoco_method == "Euler" and row.mechkit_closure <= 1e-11 < row.mujoco_closure
    assert row.difference < 1e-2


ROW = SimulationSpeed("four_bar", 0.002, 150, 3.0, 450.0, 7e-9, 1e-13, 4e-8)


def test_the_section_has_one_row_per_mechanism_with_its_ratio():
    text = markdown([ROW, SimulationSpeed("five_bar", 0.002, 150, 4.0, 200.0, 1e-8, 1e-13, 1e-7)])
    lines = text.splitlines()
    assert lines[0] == HEADING
    rows = [line for line in lines if line.startswith(("| four_bar", "| five_bar"))]
    assert len(rows) == 2 and all(row.count("|") == lines[lines.index(rows[0]) - 2].count("|") for row in rows)
    assert rows[0].split(" | ")[6] == "150" and rows[1].split(" | ")[6] == "50"  # 450 / 3 and 200 / 4


def test_the_section_replaces_its_former_text_and_keeps_the_rest(tmp_path):
    """Written into a page that has it: the old section goes, what follows stays; into one without: appended."""
    page = tmp_path / "benchmarks.md"
    page.write_text(f"# Benchmarks\n\nintro\n\n{HEADING}\n\nold table\n\n## Next\n\nkept\n")
    write_section(page, [ROW])
    text = page.read_text()
    assert "old table" not in text and text.count(HEADING) == 1 and text.endswith("## Next\n\nkept\n")
    assert text.startswith("# Benchmarks\n\nintro\n\n" + markdown([ROW]))
    other = tmp_path / "other.md"
    other.write_text("# Other\n")
    write_section(other, [ROW])
    assert other.read_text() == "# Other\n\n" + markdown([ROW])
