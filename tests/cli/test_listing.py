"""`mechkit list`."""

from __future__ import annotations

from mechkit.cli import main


def test_list_names_the_calibration_mechanisms(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    assert "four_bar" in out and "five_bar" in out
