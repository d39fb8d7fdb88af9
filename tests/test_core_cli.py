"""The command line: contract keys, bad input as one line and a non-zero exit, nothing half-written."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from mechkit.cli import main

CONTRACT = {"name", "nq", "nv", "actuated", "closures", "dof", "dof_gruebler", "redundant_constraints", "checks"}


def run(*args):
    return subprocess.run([sys.executable, "-m", "mechkit", *args], check=False, capture_output=True, text=True)


def test_list_names_the_calibration_mechanisms(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    assert "four_bar" in out and "five_bar" in out


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


def test_report_with_spatial_rows_counts_redundancy(capsys):
    assert main(["report", "four_bar", "--set", "rows=spatial", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["dof"] == 1 and r["redundant_constraints"] == 3 and r["closures"][0]["rows"] == 5


@pytest.mark.parametrize("args, needle", [
    (["report", "four_bar", "--set", "crank=-1"], "'crank'"),
    (["report", "four_bar", "--set", "wheels=3"], "'wheels'"),
    (["report", "four_bar", "--set", "crank"], "name=value"),
    (["report", "nine_bar"], "no such mechanism"),
])
def test_bad_input_is_one_line_and_exit_2(args, needle):
    out = run(*args)
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("mechkit: error:") and needle in lines[0], out.stderr


def test_urdf_writes_the_generated_file(tmp_path):
    path = tmp_path / "fb.urdf"
    assert main(["urdf", "four_bar", "--set", "crank=0.12", "-o", str(path)]) == 0
    text = path.read_text()
    assert "<mechkit:loop" in text and 'xyz="0.12 0 0"' in text


def test_failed_urdf_writes_nothing(tmp_path):
    path = tmp_path / "bad.urdf"
    assert main(["urdf", "four_bar", "--set", "ground=2", "-o", str(path)]) == 2
    assert not path.exists() and not list(tmp_path.iterdir())


def test_snapshot_is_self_contained_html(tmp_path):
    path = tmp_path / "snap.html"
    assert main(["snapshot", "five_bar", "-o", str(path)]) == 0
    html = path.read_text()
    assert html.startswith("<!DOCTYPE html>") and "MeshCat.Viewer" in html
    assert "<script src=" not in html and "<link " not in html  # nothing fetched from elsewhere


def test_written_files_have_an_ordinary_mode(tmp_path):
    import os
    import stat

    path = tmp_path / "fb.urdf"
    assert main(["urdf", "four_bar", "-o", str(path)]) == 0
    umask = os.umask(0)
    os.umask(umask)
    assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~umask
