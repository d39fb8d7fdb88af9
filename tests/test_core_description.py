"""Description layer: xacro -> URDF with loop declarations; every consumer accepts the URDFs."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

import mechkit
from mechkit.base.exceptions import InvalidParameters, MalformedDescription
from mechkit.base.resources import urdf_dir
from mechkit.catalog.registry import specs
from mechkit.sources.urdf import build_model, parse_loops

NAMES = list(specs())


@pytest.mark.parametrize("name", NAMES)
def test_committed_urdf_matches_the_xacro_template(name):
    path = urdf_dir() / f"{name}.urdf"
    assert path.exists(), f"urdf/{name}.urdf missing: run python tools/generate_urdfs.py {name}"
    assert path.read_text() == specs()[name].default_urdf(), f"urdf/{name}.urdf is stale: run tools/generate_urdfs.py"


@pytest.mark.parametrize("name", NAMES)
def test_urdfdom_accepts(name, tmp_path):
    # the venv's bin (where pip puts urdfdom's check_urdf) may not be on PATH
    exe = shutil.which("check_urdf", path=os.pathsep.join([os.path.dirname(sys.executable), os.environ.get("PATH", "")]))
    if exe is None:
        pytest.skip("check_urdf (urdfdom) not on PATH")
    out = subprocess.run([exe, str(urdf_dir() / f"{name}.urdf")], check=False, capture_output=True, text=True)
    assert out.returncode == 0 and "Successfully Parsed" in out.stdout, out.stdout + out.stderr


@pytest.mark.parametrize("name", NAMES)
def test_yourdfpy_accepts(name):
    yourdfpy = pytest.importorskip("yourdfpy")
    robot = yourdfpy.URDF.load(str(urdf_dir() / f"{name}.urdf"), load_meshes=False, build_scene_graph=False)
    assert robot.validate()


@pytest.mark.parametrize("name", NAMES)
def test_mujoco_compiles(name):
    mujoco = pytest.importorskip("mujoco")
    model = mujoco.MjModel.from_xml_string((urdf_dir() / f"{name}.urdf").read_text())
    assert model.njnt == build_model((urdf_dir() / f"{name}.urdf").read_text()).njoints - 1


@pytest.mark.parametrize("name", NAMES)
def test_loops_parse_into_typed_records(name):
    loops = parse_loops((urdf_dir() / f"{name}.urdf").read_text())
    assert loops, "a mechanism of mechkit has at least one loop closure"
    for loop in loops:
        assert loop.kind in ("revolute", "prismatic", "spherical", "hooke", "weld")


FOUR_BAR = (urdf_dir() / "four_bar.urdf").read_text()
LOOP = '<mechkit:loop axis="0 -1 0" frame_a="coupler_C" frame_b="rocker_C" name="C" rows="planar" type="revolute"/>'


@pytest.mark.parametrize("replacement, message", [
    (LOOP.replace('frame_b="rocker_C"', 'frame_b="nowhere"'), "frame_b 'nowhere' is not a link"),
    (LOOP.replace('type="revolute"', 'type="screw"'), "type 'screw'"),
    (LOOP.replace(' axis="0 -1 0"', ""), "missing attribute 'axis'"),
    (LOOP.replace('axis="0 -1 0"', 'axis="0 0"'), "not a non-zero 3-vector"),
    (LOOP.replace('rows="planar"', 'rows="some"'), "rows 'some'"),
    (LOOP.replace('frame_b="rocker_C"', 'frame_b="coupler_C"'), "the same link"),
])
def test_malformed_loop_declarations_are_named(replacement, message):
    assert LOOP in FOUR_BAR
    with pytest.raises(MalformedDescription, match=message):
        parse_loops(FOUR_BAR.replace(LOOP, replacement))


def test_urdfdom_complaints_are_errors():
    broken = FOUR_BAR.replace('<joint name="coupler" type="revolute">', '<joint name="coupler" type="revolving">')
    with pytest.raises(MalformedDescription):
        build_model(broken)


def test_not_xml_is_an_error():
    with pytest.raises(MalformedDescription, match="not well-formed"):
        parse_loops("<robot><link></robot>")


@pytest.mark.parametrize("params, name", [
    ({"crank": -0.1}, "crank"),
    ({"coupler": 0.0}, "coupler"),
    ({"ground": float("nan")}, "ground"),
    ({"gears": 3}, "gears"),
    ({"ground": 2.0}, "ground/crank/coupler/rocker"),
])
def test_bad_parameters_name_the_parameter(params, name):
    with pytest.raises(InvalidParameters) as err:
        mechkit.load("four_bar", **params)
    assert err.value.name == name


def test_unknown_mechanism():
    with pytest.raises(InvalidParameters, match="no such mechanism"):
        mechkit.load("eleven_bar")


def test_a_linkage_that_cannot_assemble_is_a_clear_error():
    # crank at pi puts B 0.55 m from D: coupler + rocker (0.28 + 0.22) cannot reach
    m = mechkit.load("four_bar", ground=0.45)
    with pytest.raises(mechkit.ClosureNotConverged) as err:
        m.assemble([np.pi])
    assert err.value.residual > err.value.tol
