"""What the commands share (`mechkit.cli.common`): NAME|PATH, --set, --actuated; a bad file is one line."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from tests_support import FIXTURES, ROOT, SLIDER_CRANK, written

import mechkit
from mechkit.cli import main

CONTRACT_KEYS = {"name", "nq", "nv", "actuated", "closures", "dof", "dof_gruebler", "redundant_constraints", "checks"}


def test_cli_takes_a_path_set_and_actuated(tmp_path, capsys):
    assert main(["report", str(FIXTURES / "watt_six_bar.urdf.xacro"), "--set", "theta=0.8", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert CONTRACT_KEYS | {"idle", "loops", "rows_avoided"} <= set(r)
    assert r["dof"] == 1 and r["rows_avoided"] == 6
    assert main(["report", str(FIXTURES / "slider_crank.urdf"), "--actuated", "slider", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["actuated"] == ["slider"]
    assert main(["report", str(FIXTURES / "slider_crank.urdf"), "--set", "rows=spatial", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["loops"][0]["chosen"] == "forced" and r["redundant_constraints"] == 3 and r["dof"] == 1
    out = tmp_path / "watt.xml"
    assert main(["export", str(FIXTURES / "watt_six_bar.urdf.xacro"), "--format", "mjcf", "-o", str(out)]) == 0
    again = mechkit.load(out)
    assert again.mobility().dof == 1 and again.actuated == ("crank",) and again.structure.kutzbach == 1


@pytest.mark.parametrize(
    "args, needle",
    [
        (["report", "tests/fixtures/nowhere.urdf"], "no such file"),
        (["report", "tests/fixtures"], "directory"),
        (["snapshot", "UNACTUATED", "--q", "0.3"], "unactuated"),
        (["urdf", "tests/fixtures/slider_crank.urdf", "--set", "crank=1"], "not a xacro file"),
    ],
)
def test_cli_errors_are_one_line(args, needle, tmp_path):
    if "UNACTUATED" in args:
        text = (
            SLIDER_CRANK[: SLIDER_CRANK.index("<transmission")]
            + SLIDER_CRANK[SLIDER_CRANK.index("</transmission>") + 15 :]
        )
        args = [a if a != "UNACTUATED" else str(written(tmp_path, text)) for a in args] + [
            "-o",
            str(tmp_path / "s.html"),
        ]
    out = subprocess.run(
        [sys.executable, "-m", "mechkit", *args], capture_output=True, text=True, check=False, cwd=ROOT
    )
    assert out.returncode == 2, out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0] and "Traceback" not in out.stderr
    assert not (tmp_path / "s.html").exists()


def test_an_unread_closure_is_refused_and_with_the_option_warned_in_one_line():
    from tests_support import FIXTURES, refused, run_mechkit

    path = str(FIXTURES / "closures" / "four_bar_drake_bushing.sdf")
    refused(
        run_mechkit("report", path),
        "four_bar_drake_bushing.sdf:",
        "<drake:linear_bushing_rpy>",
        "--ignore-unknown-closures",
    )
    out = run_mechkit("report", path, "--ignore-unknown-closures")
    warnings = [line for line in out.stderr.splitlines() if line.startswith("mechkit: warning: ")]
    assert out.returncode == 0 and "Traceback" not in out.stderr
    assert len(warnings) == 1 and "left with 3 degree(s) of freedom" in warnings[0], out.stderr
