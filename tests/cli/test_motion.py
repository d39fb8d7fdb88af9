"""`mechkit motion` on every registered mechanism's default scene: the peak table, the table file and the
plot; bad input is one line and exit 2, with nothing written."""

from __future__ import annotations

import numpy as np
import pytest
from tests_support import FIXTURES

from mechkit import motion
from mechkit.catalog.registry import names
from mechkit.cli import main

#: The deployable's fold scene takes about 40 s to assemble (201 poses of a 66-coordinate model).
SLOW = {"deployable_9rr12uru"}


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n for n in names()])
def test_default_scene(name, tmp_path, capsys):
    out = tmp_path / "m.parquet"
    assert main(["motion", name, "--samples", "6", "-o", str(out), "--plot", str(tmp_path / "m.png")]) == 0
    text = capsys.readouterr().out
    result = motion.read_parquet(out)
    assert result.mechanism == name and len(result.t) == 6
    for joint in result.joints:
        assert any(line.split()[0] == joint for line in text.splitlines()), joint
    good = np.isfinite(result.efforts).all(axis=1)
    assert good.sum() + len(result.failures) == 6 and good.sum() >= 5
    assert (tmp_path / "m.png").stat().st_size > 1000


def test_inputs_csv_and_csv_output(tmp_path, capsys):
    law = tmp_path / "law.csv"
    t = np.linspace(0.0, 1.0, 11)
    law.write_text("t,crank\n" + "".join(f"{x!r},{0.6 + 0.2 * x * x!r}\n" for x in t.tolist()))
    out = tmp_path / "m.csv"
    assert main(["motion", "four_bar", "--inputs", str(law), "-o", str(out)]) == 0
    r = motion.read_csv(out)
    assert np.allclose(r.v[:, 0], 0.4 * t, atol=1e-12) and np.allclose(r.a[:, 0], 0.4, atol=1e-10)


@pytest.mark.parametrize(
    "args, needle",
    [
        (["--inputs", "missing.csv"], "missing.csv"),
        (["--scene", "dance"], "--scene: "),
        (["--samples", "1"], "--samples: "),
        (["-o", "OUT.txt"], "parquet"),
        (["--plot", "OUT.png", "--joints", "nope"], "nope"),
        (["--joints", "crank"], "'--joints': chooses the joints --plot shows: give --plot too"),  # was ignored
    ],
)
def test_bad_input(args, needle, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    samples = [] if "--samples" in args else ["--samples", "4"]
    assert main(["motion", "four_bar", *samples, *args]) == 2
    err = capsys.readouterr().err.strip()
    assert needle in err and len(err.splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("fixture", ["slider_crank.urdf", "rssr.xml"])
def test_a_file_mechanism(fixture, tmp_path, capsys):
    """NAME|PATH: a mechanism from a file gets the generic sweep; a prismatic slider carries no axial force;
    where the inputs leave a freedom (the RSSR's coupler spin) no sample succeeds: one line, exit 2."""
    path = FIXTURES / fixture
    out = tmp_path / "m.parquet"
    status = main(["motion", str(path), "--samples", "6", "-o", str(out)])
    if fixture == "rssr.xml":  # the coupler's spin about its own axis is an idle freedom: no sample has a motion
        err = capsys.readouterr().err.strip()
        assert status == 2 and "do not determine" in err and len(err.splitlines()) == 1 and not out.exists()
    else:
        result = motion.read_parquet(out)
        assert status == 0 and result.source == "scene sweep" and np.isfinite(result.efforts).all()
        peak = {p.joint: p for p in motion.peaks(result)}["slider"]
        assert peak.values["axial_force"] < 1e-12 * peak.values["force"]


@pytest.mark.parametrize(
    "module, args", [("pandas", ["-o", "m.csv"]), ("pyarrow", ["-o", "m.parquet"]), ("matplotlib", ["--plot", "m.png"])]
)
def test_a_missing_library_is_refused_before_the_study(module, args, tmp_path, capsys, monkeypatch):
    """An output whose library is not installed is refused in one line before any sample is computed."""
    monkeypatch.setitem(__import__("sys").modules, module, None)  # import fails as if not installed
    monkeypatch.chdir(tmp_path)
    assert main(["motion", "four_bar", "--samples", "6", *args]) == 2
    out, err = capsys.readouterr()
    assert "peak reactions" not in out and err.count("\n") == 1 and "pip install" in err
    assert list(tmp_path.iterdir()) == []


def test_hold_keeps_the_platform_level_on_a_rolling_carrier(tmp_path, capsys):
    """`--hold platform` on the spherical platform carried by a rolling, pitching, heaving base (a CSV of the
    carrier's pose): the inputs found keep the platform level to 1e-10 rad at every sample, and the carrier's
    vertical force brackets the mechanism's weight (the heave's accelerations about it)."""
    import mechkit

    carrier = tmp_path / "carrier.csv"
    t = np.linspace(0.0, 4.0, 21)
    rows = [
        f"{s:.3f},0,0,{0.05 * np.sin(s):.12f},{0.1 * np.sin(0.8 * s):.12f},{0.05 * np.sin(1.1 * s):.12f},0" for s in t
    ]
    carrier.write_text("t,x,y,z,roll,pitch,yaw\n" + "\n".join(rows) + "\n")
    out = tmp_path / "held.csv"
    argv = ["motion", "spherical_2dof", "--base", "moving", "--base-motion", str(carrier), "--hold", "platform"]
    assert main([*argv, "-o", str(out)]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert "platform held level" in first
    assert float(first.split("tilt left <= ")[1].split(" rad")[0]) < 1e-10
    result = mechkit.motion.read_csv(out)
    weight = sum(i.mass for i in mechkit.load("spherical_2dof").model.inertias) * 9.81
    force = result.effort("base_z")
    assert force.min() < weight < force.max() and np.abs(force - weight).max() < 0.1 * weight
    assert main(["motion", "spherical_2dof", "--hold", "platform"]) == 2
    assert "--hold" in capsys.readouterr().err
