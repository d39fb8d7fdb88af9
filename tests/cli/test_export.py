"""`mechkit export`: both formats written; the Extended URDF's sidecar never overwrites what was asked for."""

from __future__ import annotations

import pytest
import yaml

from mechkit.cli import main

mujoco = pytest.importorskip("mujoco")
from tests_support import refused, run_mechkit


def test_cli_export_writes_both_formats(tmp_path, capsys):
    assert main(["export", "four_bar", "--format", "mjcf", "-o", str(tmp_path / "fb.xml")]) == 0
    assert main(["export", "four_bar", "--format", "extended-urdf", "-o", str(tmp_path / "fb.urdf")]) == 0
    out = capsys.readouterr().out
    assert "fb.xml" in out and "fb.yaml" in out
    mujoco.MjModel.from_xml_path(str(tmp_path / "fb.xml"))
    sidecar = yaml.safe_load((tmp_path / "fb.yaml").read_text())
    assert sidecar == {
        "closed_loop": [["coupler_C", "rocker_C"]],
        "type": ["3d"],
        "name_mot": ["crank"],
        "joint_name": [],
        "joint_type": [],
    }


def test_extended_urdf_sidecar_cannot_overwrite_the_urdf(tmp_path):
    target = tmp_path / "z.yaml"
    target.write_text("keep")
    refused(run_mechkit("export", "five_bar", "--format", "extended-urdf", "-o", str(target)), "sidecar")
    assert target.read_text() == "keep" and sorted(p.name for p in tmp_path.iterdir()) == ["z.yaml"]
    out = run_mechkit("export", "five_bar", "--format", "extended-urdf", "-o", str(tmp_path / "z.urdf"))
    assert out.returncode == 0 and (tmp_path / "z.urdf").exists() and (tmp_path / "z.yaml").read_text() != "keep"
