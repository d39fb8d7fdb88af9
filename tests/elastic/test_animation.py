"""A mode animated in an offline meshcat page, from the command line."""

from __future__ import annotations

import json

from mechkit.cli import main


def test_modes_and_stiffness_commands(tmp_path, capsys):
    page = tmp_path / "mode.html"
    assert main(["modes", "four_bar", "-n", "3", "--animate", str(page), "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert len(r["modes"]) == 3 and r["modes"][0]["frequency_hz"] > 100 and page.stat().st_size > 100_000
    assert "mode 1" in page.read_text()
    assert main(["stiffness", "parallel_2t1r", "--body", "platform", "--at", "R11=0.2,R21=0.35,R31=0.5", "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["held"]["y"] >= s["free"]["y"] > 0
    assert main(["stiffness", "four_bar", "--body", "nowhere"]) == 2
    assert "no such link" in capsys.readouterr().err
