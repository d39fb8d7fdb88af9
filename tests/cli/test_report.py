"""`mechkit report`: the JSON contract."""

from __future__ import annotations

import json

import pytest

from mechkit.catalog.registry import names
from mechkit.cli import main

CONTRACT = {"name", "nq", "nv", "actuated", "closures", "dof", "dof_gruebler", "redundant_constraints", "checks"}


@pytest.mark.parametrize("name, dof", [("four_bar", 1), ("five_bar", 2)])
def test_report_json_contract(name, dof, capsys):
    assert main(["report", name, "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert CONTRACT <= set(r)
    assert r["dof"] == dof == r["dof_gruebler"]
    assert r["redundant_constraints"] == 0
    assert all(isinstance(v, float) for v in r["checks"].values())
    assert r["checks"]["closure_residual"] < 1e-12
    assert r["checks"]["kkt_vs_proximal"] < 1e-9
    assert r["checks"]["inverse_forward_roundtrip"] < 1e-9
    assert {c["rows"] for c in r["closures"]} == {2}


@pytest.mark.parametrize("name", names())
def test_every_registered_mechanism_reports_from_the_command_line(name, capsys):
    """Under the command line's floating-point traps (overflow, invalid, division raise; underflow flushes
    to zero), every registered mechanism's report runs to the end and its checks are numbers."""
    assert main(["report", name, "--json"]) == 0
    out = capsys.readouterr()
    assert out.err == ""
    assert all(isinstance(v, float) for v in json.loads(out.out)["checks"].values())


def test_report_with_spatial_rows_counts_redundancy(capsys):
    assert main(["report", "four_bar", "--set", "rows=spatial", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["dof"] == 1 and r["redundant_constraints"] == 3 and r["closures"][0]["rows"] == 5
