"""`mechkit validate`: the JSON contract, the text form, files as well as names, bad input as one line."""

from __future__ import annotations

import contextlib
import io
import json

import pytest
from tests_support import FIXTURES, PANDA

from mechkit.cli import main

KEYS = {"name", "skcs", "max_relative_difference", "samples", "us_per_sample"}
SKC_KEYS = {"bodies", "released", "actuators", "unknowns", "equations"}


def test_validate_json_contract(capsys):
    assert main(["validate", "parallel_2t1r", "--json", "--samples", "3"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert KEYS <= set(r) and r["name"] == "parallel_2t1r"
    assert all(SKC_KEYS <= set(s) for s in r["skcs"])
    assert [s["released"] for s in r["skcs"][:3]] == [["R43"], ["R23"], []]
    assert r["samples"] == 3 and r["max_relative_difference"] < 1e-8 and not r["determinacy_mismatches"]
    assert set(r["us_per_sample"]) == {"second opinion (SOC virtual work)", "constrained RNEA + determinacy"}
    assert all(us > 0 for us in r["us_per_sample"].values())
    # the determined SKCs fix all their unknowns; the out-of-plane block leaves some free
    assert all(not s["indeterminate"] for s in r["skcs"] if s["kind"] == "determined")
    (under,) = [s for s in r["skcs"] if s["kind"] == "under"]
    assert under["indeterminate"] and {u.split(".")[1] for u in under["indeterminate"]} <= {"fy", "mx", "mz"}


def test_validate_text_names_each_skc(capsys):
    assert main(["validate", "four_bar", "--samples", "2", "--level", "body"]) == 0
    out = capsys.readouterr().out
    assert "SKC1 [determined] bodies: coupler_link, rocker_link" in out
    assert "released: coupler" in out and "indeterminate" in out and "us per sample" in out


@pytest.mark.parametrize("file", ["slider_crank.urdf", "watt_six_bar.urdf.xacro", "rssr.xml", "leg.urdf"])
def test_validate_files_from_the_sources_fixtures(file, capsys):
    assert main(["validate", str(FIXTURES / file), "--json", "--samples", "3"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["samples"] >= 1 and not r["determinacy_mismatches"]
    assert r["max_relative_difference"] < 1e-8, (r["worst"], r["max_relative_difference"])


@pytest.mark.parametrize(
    "args, what",
    [
        (["four_bar", "--samples", "0"], "--samples"),
        (["four_bar", "--scene", "nowhere"], "scene"),
        (["no_such_mechanism"], "no_such_mechanism"),
    ],
)
def test_validate_bad_input_is_one_line(args, what, capsys):
    assert main(["validate", *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and what in err and "Traceback" not in err


def test_validate_of_a_tree_with_no_loop_is_one_line():
    """example-robot-data's Panda: nothing to cross-check, said in one line, exit 2, no traceback."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(["validate", str(PANDA)])
    lines = err.getvalue().strip().splitlines()
    assert code == 2 and out.getvalue() == "" and len(lines) == 1 and "has no loop closure" in lines[0]
