"""`mechkit simulate`: the summary printed (energy balance, closure residual), the table written, errors in
one line, the help's examples."""

from __future__ import annotations

import pytest

from mechkit.cli import main


def test_simulate_four_bar_writes_parquet(tmp_path, capsys):
    pd = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    out = tmp_path / "free.parquet"
    assert (
        main(["simulate", "four_bar", "--duration", "0.2", "-o", str(out), "--plot", str(tmp_path / "free.png")]) == 0
    )
    text = capsys.readouterr().out
    assert "energy balance: drift" in text and "closure residual: max" in text
    df = pd.read_parquet(out)
    for column in (
        "t",
        "q/crank",
        "reaction/C/fx",
        "closure_residual",
        "energy/kinetic",
        "energy/balance",
        "power/friction",
    ):
        assert column in df.columns, column
    assert df["closure_residual"].max() <= 1e-10
    assert (tmp_path / "free.png").stat().st_size > 10_000


def test_simulate_with_friction_torques_csv_and_latch(tmp_path, capsys):
    law = tmp_path / "torque.csv"
    law.write_text("t,crank\n0,0.05\n0.3,0.05\n0.6,0.05\n1,0.05\n")
    assert (
        main(
            [
                "simulate",
                "four_bar",
                "--duration",
                "0.1",
                "--torques",
                str(law),
                "--friction",
                "0.1,0.005",
                "--latch",
                "crank=0.5",
                "-o",
                str(tmp_path / "t.csv"),
            ]
        )
        == 0
    )
    text = capsys.readouterr().out
    assert "dissipated" in text and (tmp_path / "t.csv").exists()


def test_errors_are_one_line(capsys):
    assert main(["simulate", "four_bar", "--duration", "-1"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechkit: error:") and err.count("\n") == 1


def test_help_ends_with_two_examples(capsys):
    with pytest.raises(SystemExit):
        main(["simulate", "--help"])
    lines = capsys.readouterr().out.rstrip().splitlines()
    assert lines[-3] == "examples:" and all(line.startswith("  mechkit simulate") for line in lines[-2:])
