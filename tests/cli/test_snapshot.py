"""`mechkit snapshot`: self-contained HTML; a URDF file's meshes found beside it or on --mesh-path;
--png in a real browser."""

from __future__ import annotations

import pytest
from viz.in_browser import assert_shows_a_mechanism, needs_browser
from viz.mesh_urdf import MESHES
from viz.meshcat_pages import page_objects

import mechkit
from mechkit.cli import main
from mechkit.viz.meshes import MissingMesh


def test_snapshot_is_self_contained_html(tmp_path):
    path = tmp_path / "snap.html"
    assert main(["snapshot", "five_bar", "-o", str(path)]) == 0
    html = path.read_text()
    assert html.startswith("<!DOCTYPE html>") and "MeshCat.Viewer" in html
    assert "<script src=" not in html and "<link " not in html  # nothing fetched from elsewhere


@needs_browser
@pytest.mark.parametrize("name", list(mechkit.specs()))
def test_snapshot_png_shows_the_mechanism(name, tmp_path):
    """`mechkit snapshot NAME --png out.png`, offline."""
    png = tmp_path / f"{name}.png"
    assert main(["snapshot", name, "--png", str(png)]) == 0
    assert_shows_a_mechanism(png)
    assert [p.name for p in tmp_path.iterdir()] == [png.name]  # its temporary page is gone


def test_snapshot_command_of_a_urdf_file(tmp_path, capsys):
    """`mechkit snapshot arm.urdf`: the STL beside the file is found; the package:// OBJ with --mesh-path,
    else a warning and a placeholder (exit 0 both ways)."""
    from mechkit.cli import main

    urdf = str(MESHES / "arm.urdf")
    assert main(["snapshot", urdf, "-o", str(tmp_path / "a.html"), "--mesh-path", str(MESHES.parent)]) == 0
    objects = page_objects((tmp_path / "a.html").read_text())
    assert sorted(o["geometries"][0].get("format") for p, o in objects.items() if "/links/" in p) == ["obj", "stl"]
    with pytest.warns(MissingMesh, match="package://meshes/box.obj"):
        assert main(["snapshot", urdf, "-o", str(tmp_path / "b.html")]) == 0
    objects = page_objects((tmp_path / "b.html").read_text())
    kinds = sorted(o["geometries"][0]["type"] for p, o in objects.items() if "/links/" in p)
    assert kinds == ["SphereGeometry", "_meshfile"]
