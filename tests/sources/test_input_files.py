"""`mechkit.sources.input_files`: the files a description is read from, its sidecar and includes among
them, references that are not local files left out, unreadable XML naming only itself."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from tests_support import FIXTURES, ROOT

from mechkit.sources.input_files import description_files


def test_a_urdf_with_its_sidecar(tmp_path):
    for name in ("leg.urdf", "leg.yaml"):
        shutil.copy(FIXTURES / name, tmp_path / name)
    assert description_files(tmp_path / "leg.urdf") == [tmp_path / "leg.urdf", tmp_path / "leg.yaml"]


def test_a_xacro_with_its_includes_recursively(tmp_path):
    (tmp_path / "inner").mkdir()
    (tmp_path / "inner" / "deep.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>')
    (tmp_path / "macros.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:include filename="inner/deep.xacro"/></robot>'
    )
    (tmp_path / "top.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="macros.xacro"/>'
        '<xacro:include filename="$(find some_pkg)/urdf/x.xacro"/>'
        '<link name="a"><visual><geometry><mesh filename="package://p/m.stl"/></geometry></visual></link></robot>'
    )
    assert description_files(tmp_path / "top.urdf.xacro") == [
        tmp_path / "top.urdf.xacro",
        tmp_path / "macros.xacro",
        tmp_path / "inner" / "deep.xacro",
    ]


def test_mjcf_includes_and_meshes_under_its_meshdir(tmp_path):
    (tmp_path / "assets").mkdir()
    (tmp_path / "assets" / "part.stl").write_bytes(b"solid x\nendsolid x\n")
    (tmp_path / "body.xml").write_text("<mujoco/>")
    (tmp_path / "model.xml").write_text(
        '<mujoco><compiler meshdir="assets"/><include file="body.xml"/>'
        '<asset><mesh name="p" file="part.stl"/><mesh name="q" file="missing.stl"/></asset></mujoco>'
    )
    assert description_files(tmp_path / "model.xml") == [
        tmp_path / "model.xml",
        tmp_path / "body.xml",
        tmp_path / "assets" / "part.stl",
    ]


def test_sdformat_include_uri_and_a_link_followed(tmp_path):
    (tmp_path / "part.sdf").write_text("<sdf/>")
    (tmp_path / "world.sdf").write_text("<sdf><model name='m'><include><uri>part.sdf</uri></include></model></sdf>")
    (tmp_path / "alias.sdf").symlink_to(tmp_path / "world.sdf")
    assert description_files(tmp_path / "alias.sdf") == [tmp_path / "world.sdf", tmp_path / "part.sdf"]


def test_unreadable_or_missing_files(tmp_path):
    (tmp_path / "broken.urdf").write_text("<robot><link")
    assert description_files(tmp_path / "broken.urdf") == [tmp_path / "broken.urdf"]
    assert description_files(tmp_path / "none.urdf") == []


def test_a_registered_template_names_its_macros():
    files = description_files(ROOT / "xacro" / "four_bar.urdf.xacro")
    assert files[0].name == "four_bar.urdf.xacro" and (ROOT / "xacro" / "macros.xacro").resolve() in files


def test_a_xacro_glob_include_names_every_file_xacro_opens(tmp_path):
    """xacro includes every file a pattern matches; the list holds each, as xacro's own record does."""
    xacro = pytest.importorskip("xacro")
    (tmp_path / "parts").mkdir()
    for name in ("g_1.xacro", "g_2.xacro"):
        (tmp_path / "parts" / name).write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>')
    (tmp_path / "top.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="parts/g_*.xacro"/><link name="a"/></robot>'
    )
    files = description_files(tmp_path / "top.urdf.xacro")
    assert files == [tmp_path / "top.urdf.xacro", tmp_path / "parts" / "g_1.xacro", tmp_path / "parts" / "g_2.xacro"]
    xacro.all_includes.clear()
    xacro.process_file(str(tmp_path / "top.urdf.xacro"))
    assert sorted(Path(p).resolve() for p in xacro.all_includes) == files[1:]


def test_a_nested_mjcf_include_is_the_file_mujoco_reads(tmp_path):
    """MuJoCo 4 reads a nested include beside the main file first, then beside the including file: with a
    file of that name in both places the list names the one MuJoCo compiles (an empty one fails it)."""
    mujoco = pytest.importorskip("mujoco")
    (tmp_path / "sub").mkdir()
    (tmp_path / "main.xml").write_text('<mujoco model="m"><include file="sub/a.xml"/></mujoco>')
    (tmp_path / "sub" / "a.xml").write_text('<mujoco><include file="b.xml"/></mujoco>')
    body = '<mujoco><worldbody><body><joint type="hinge"/><geom size="0.1"/></body></worldbody></mujoco>'
    (tmp_path / "sub" / "b.xml").write_text(body)
    assert mujoco.MjModel.from_xml_path(str(tmp_path / "main.xml")).njnt == 1
    assert description_files(tmp_path / "main.xml")[2] == tmp_path / "sub" / "b.xml"
    (tmp_path / "b.xml").write_text("<mujoco/>")  # now beside the main file: MuJoCo reads this one
    with pytest.raises(ValueError, match="b.xml"):
        mujoco.MjModel.from_xml_path(str(tmp_path / "main.xml"))
    assert description_files(tmp_path / "main.xml")[2] == tmp_path / "b.xml"
