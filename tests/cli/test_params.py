"""`mechkit params`: defaults, units, ranges of a registered mechanism; a file's xacro arguments."""

from __future__ import annotations

import json

from tests_support import FIXTURES

from mechkit.catalog.ranges import param_ranges
from mechkit.catalog.registry import get_spec
from mechkit.cli import main
from mechkit.sources import xacro_args


def test_cli_params_table_and_json(capsys):
    assert main(["params", "four_bar"]) == 0
    out = capsys.readouterr().out
    assert "ground" in out and "(0, 0.6)" in out and "kg/m^3" in out and "(ours)" in out
    assert main(["params", "rocket_gimbal", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    row = next(r for r in rows if r["name"] == "length_a")
    expected = param_ranges(get_spec("rocket_gimbal").params)["length_a"]
    assert expected.lower is not None and expected.upper is not None  # bounded both ways by the class
    assert (
        row["unit"] == "m"
        and row["range"] == expected.text()
        and row["value"] == get_spec("rocket_gimbal").params().length_a
    )
    assert main(["params", "no_such"]) == 2
    assert "no such mechanism" in capsys.readouterr().err


def test_cli_params_of_files(capsys):
    """A xacro file lists its xacro arguments with their defaults; a URDF has none."""
    xacro = FIXTURES / "watt_six_bar.urdf.xacro"
    assert main(["params", str(xacro), "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert {r["name"]: r["value"] for r in rows} == xacro_args(xacro) and rows
    assert main(["params", str(FIXTURES / "slider_crank.urdf")]) == 0
    assert "no parameters" in capsys.readouterr().out
