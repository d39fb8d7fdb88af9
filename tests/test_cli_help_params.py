"""`--help` of every command ends with two working examples; `mechkit params` states defaults, units, ranges."""

from __future__ import annotations

import json
import shlex
from pathlib import Path

import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.ranges import param_ranges
from mechkit.catalog.registry import get_spec
from mechkit.cli import COMMANDS, build_parser, main
from mechkit.sources import xacro_args


def _subparsers() -> dict[str, object]:
    parser = build_parser()
    action = next(a for a in parser._actions if a.dest == "command")
    return dict(action.choices)


def test_every_command_ends_its_help_with_two_examples_that_parse():
    subs = _subparsers()
    assert len(subs) == len(COMMANDS)
    for name, sub in subs.items():
        lines = sub.format_help().rstrip().splitlines()
        assert lines[-3] == "examples:", (f"`mechkit {name} --help` must end with two examples: pass "
                                          f"**mechkit.cli.common.examples(cmd1, cmd2) to its sub.add_parser")
        for line in lines[-2:]:
            argv = shlex.split(line.split("|")[0])
            assert argv[:2] == ["mechkit", name], line
            args = build_parser().parse_args(argv[1:])  # exits (SystemExit) on a bad example
            assert args.command == name


def test_four_bar_ranges_are_the_loop_closure_inequality():
    """The four-bar class accepts a link up to the sum of the other three: the bisected bounds are those sums."""
    r = param_ranges(get_spec("four_bar").params)
    p = get_spec("four_bar").params()
    lengths = {"ground": p.ground, "crank": p.crank, "coupler": p.coupler, "rocker": p.rocker}
    for name in lengths:
        others = sum(v for k, v in lengths.items() if k != name)
        assert r[name].lower == 0.0 and not r[name].lower_closed
        assert r[name].upper == pytest.approx(others, abs=1e-12) and not r[name].upper_closed
    assert r["density"].text() == "> 0" and r["rows"] is None


def test_closed_and_open_bounds():
    """ten_bar: damping >= 0 (zero accepted); l56 below the wall-gap reach; a free angle has no bound."""
    r = param_ranges(get_spec("ten_bar").params)
    assert r["spring_damping"].text() == ">= 0"
    assert r["stowed_rocker"].text() == "any"
    p = get_spec("ten_bar").params()
    with pytest.raises(InvalidParameters, match="five-bar must close"):
        p.replace(l56=r["l56"].upper * (1 + 1e-4))
    p.replace(l56=r["l56"].upper * (1 - 1e-4))


def test_cli_params_table_and_json(capsys):
    assert main(["params", "four_bar"]) == 0
    out = capsys.readouterr().out
    assert "ground" in out and "(0, 0.6)" in out and "kg/m^3" in out and "(ours)" in out
    assert main(["params", "rocket_gimbal", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    row = next(r for r in rows if r["name"] == "length_a")
    expected = param_ranges(get_spec("rocket_gimbal").params)["length_a"]
    assert expected.lower is not None and expected.upper is not None  # bounded both ways by the class
    assert row["unit"] == "m" and row["range"] == expected.text() and row["value"] == get_spec("rocket_gimbal").params().length_a
    assert main(["params", "no_such"]) == 2
    assert "no such mechanism" in capsys.readouterr().err


def test_cli_params_of_files(capsys):
    """A xacro file lists its xacro arguments with their defaults; a URDF has none."""
    fixtures = Path(__file__).resolve().parent / "fixtures"
    xacro = fixtures / "watt_six_bar.urdf.xacro"
    assert main(["params", str(xacro), "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert {r["name"]: r["value"] for r in rows} == xacro_args(xacro) and rows
    assert main(["params", str(fixtures / "slider_crank.urdf")]) == 0
    assert "no parameters" in capsys.readouterr().out
