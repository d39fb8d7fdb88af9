"""A mode animated in an offline meshcat page, from the command line (`mechkit stiffness` and the rest of
`mechkit modes`: tests/cli/test_stiffness.py, tests/cli/test_modes.py)."""

from __future__ import annotations

import json

from mechkit.cli import main


def test_a_mode_animated_from_the_command_line(tmp_path, capsys):
    page = tmp_path / "mode.html"
    assert main(["modes", "four_bar", "-n", "3", "--animate", str(page), "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert len(r["modes"]) == 3 and r["modes"][0]["frequency_hz"] > 100 and page.stat().st_size > 100_000
    assert "mode 1" in page.read_text()
