"""What the commands share (`mechkit.cli.common`): NAME|PATH, --set, --actuated; a bad file is one line."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
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

    path = str(FIXTURES / "closures" / "four_bar_drake_distance.sdf")
    refused(
        run_mechkit("report", path),
        "four_bar_drake_distance.sdf:",
        "<drake:distance_constraint>",
        "--ignore-unknown-closures",
    )
    out = run_mechkit("report", path, "--ignore-unknown-closures")
    warnings = [line for line in out.stderr.splitlines() if line.startswith("mechkit: warning: ")]
    assert out.returncode == 0 and "Traceback" not in out.stderr
    assert len(warnings) == 1 and "left with 3 degree(s) of freedom" in warnings[0], out.stderr


def _four_bar_rocker_limited(tmp_path, lower: float, upper: float):
    """The packaged four-bar with its rocker's limits set to [lower, upper] (rad)."""
    text = (ROOT / "mechkit" / "urdf" / "four_bar.urdf").read_text()
    old = '<limit effort="1e6" lower="-25.0" upper="25.0" velocity="1e3"/>'
    assert text.count(old) == 1
    path = tmp_path / "four_bar_limited.urdf"
    path.write_text(text.replace(old, f'<limit effort="1e6" lower="{lower}" upper="{upper}" velocity="1e3"/>'))
    return path


def test_the_assembly_line_names_the_reference_and_the_branch(capsys):
    """report's first line (its JSON: "assembly") names the home assembly's start (the file's keyframe
    'home', the URDF's <mechkit:guess>, the spec's guess); motion says each sample continues the previous."""
    assert main(["report", str(FIXTURES / "tendon_pendulum.xml")]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0] == "assembly: the home assembly, Newton from the keyframe 'home'; within the joint limits"
    assert main(["report", str(ROOT / "mechkit" / "urdf" / "four_bar.urdf"), "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["assembly"] == {"branch": "Newton from <mechkit:guess>", "outside": []}
    assert main(["motion", "four_bar", "--samples", "4"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[1] == (
        "assembly: the home assembly, Newton from the spec's guess; within the joint limits; "
        "each sample continued from the previous sample"
    )


def test_a_branch_outside_the_limits_is_said_and_refused_where_continued(tmp_path, capsys):
    """The four-bar's home branch puts the rocker at about 1.53 rad; with the rocker limited to
    [-0.5, 0.5] (no whole turn brings it in): the report runs and its assembly line names the rocker (the
    home is the file's own pose, Newton from its <mechkit:guess>), while a motion (each sample continued
    from the previous one) and a pose --at continued from home exit 2 naming the joint, its value and the
    limits."""
    path = _four_bar_rocker_limited(tmp_path, -0.5, 0.5)
    m = mechkit.load(path)
    assert m.home_assembly.outside == ("rocker",)
    value = float(m.home_q[m.q_index("rocker")])
    assert 1.4 < value < 1.6
    assert main(["report", str(path)]) == 0
    line = "assembly: the home assembly, Newton from <mechkit:guess>; outside their limits: rocker"
    assert capsys.readouterr().out.splitlines()[0] == line
    assert main(["motion", str(path), "--samples", "4"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (
        f"mechkit: error: {m.spec.name}: the motion at t = 0 s (continued from the previous sample): joint "
        f"'rocker' at {value:.6g} is outside its limits [-0.5, 0.5] (the branch leaves them)"
    )
    at = m.assembly({"crank": 0.7})
    assert main(["stiffness", str(path), "--body", "rocker_link", "--at", "crank=0.7"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (
        f"mechkit: error: --at crank=0.7 (continued from the home assembly): joint 'rocker' at "
        f"{at.q[m.q_index('rocker')]:.6g} is outside its limits [-0.5, 0.5] (the branch leaves them)"
    )


def test_a_rocker_limit_a_whole_turn_away_is_wrapped_not_refused(tmp_path, capsys):
    """The same rocker limited to [2 pi - 0.5 + 1.5, 2 pi + 2] (its home angle plus a whole turn inside):
    the angle is wrapped into the range (same placement, same closure) and the report runs."""
    m0 = mechkit.load("four_bar")
    home = float(m0.home_q[m0.q_index("rocker")])
    path = _four_bar_rocker_limited(tmp_path, home + 2 * np.pi - 0.1, home + 2 * np.pi + 0.1)
    m = mechkit.load(path)
    assert m.home_assembly.outside == ()
    assert m.home_q[m.q_index("rocker")] == pytest.approx(home + 2 * np.pi, abs=1e-9)
    assert np.linalg.norm(m.closure_residual(m.home_q)) < 1e-12
    assert main(["report", str(path)]) == 0
    assert capsys.readouterr().out.splitlines()[0].endswith("; within the joint limits")


def test_bushings_are_rigid_by_default_and_compliant_when_asked():
    """--bushings compliant leaves the bushing four-bar's loop open (the simulator's force element holds it)."""
    from tests_support import FIXTURES, run_mechkit

    path = str(FIXTURES / "closures" / "four_bar_drake_bushing.urdf")
    for extra, dof in (((), 1), (("--bushings", "compliant"), 3)):
        out = run_mechkit("report", path, *extra)
        assert out.returncode == 0 and f"DOF numerical {dof}," in out.stdout, out.stderr


def test_base_options_put_the_mechanism_on_a_base(tmp_path, capsys):
    """--base floating with --base-inertia in a report; --base moving with --base-motion in a motion study:
    the carrier's efforts at the root joints, the carrier's weight on base_z; a base motion on a fixed
    base is refused by option."""
    assert main(["report", "spherical_2dof", "--base", "floating", "--base-inertia", "20,0.5,0.6,0.7", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["dof"] == 8 and "floating base" in r["summary"]
    base = tmp_path / "carrier.csv"
    base.write_text("t,z,roll\n" + "".join(f"{t:.2f},0,{0.1 * np.sin(t):.9f}\n" for t in np.linspace(0, 1, 11)))
    out = tmp_path / "m.csv"
    assert main(["motion", "spherical_2dof", "--base", "moving", "--base-motion", str(base), "-o", str(out)]) == 0
    assert "base CSV carrier.csv, 11 samples" in capsys.readouterr().out
    table = mechkit.motion.read_csv(out)
    weight = float(np.sum([i.mass for i in mechkit.load("spherical_2dof").model.inertias])) * 9.81
    assert np.abs(table.effort("base_z") - weight).max() < 0.05 * weight  # a slow roll: the weight, nearly
    assert main(["motion", "spherical_2dof", "--base-motion", str(base)]) == 2
    assert "--base-motion" in capsys.readouterr().err
