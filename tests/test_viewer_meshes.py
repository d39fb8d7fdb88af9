"""URDF mesh visuals: found relative to the file and through package:// with a search path, drawn where
the link is (scale and origin applied); a missing mesh is a warning and a placeholder."""

from __future__ import annotations

import base64
import itertools
import re
import warnings
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from mechkit import from_urdf
from mechkit.viz import Drawing, snapshot
from mechkit.viz.meshes import MISSING, MeshSearch, MissingMesh

umsgpack = pytest.importorskip("umsgpack")
MESHES = Path(__file__).resolve().parent / "fixtures" / "meshes"  # box.stl, box.obj: 1 x 2 x 1, corner at 0
BOX = np.array(list(itertools.product((0, 1), (0, 2), (0, 1))), dtype=float)
SCALE = np.array([0.1, 0.05, 0.2])
ORIGIN = np.array([0.3, 0.0, 0.1])  # visual origin in its link (m)
INERTIAL = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'


def arm(first: str, second: str) -> str:
    """Two revolute links, each drawn by one mesh visual."""
    def link(name, filename):
        return (f'<link name="{name}">{INERTIAL}<visual><origin xyz="{" ".join(map(str, ORIGIN))}" rpy="0 0 0.4"/>'
                f'<geometry><mesh filename="{filename}" scale="{" ".join(map(str, SCALE))}"/></geometry></visual></link>')
    return (f'<robot name="arm"><link name="base"/>{link("a", first)}{link("b", second)}'
            '<joint name="j1" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>'
            '<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>'
            '<joint name="j2" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0.5 0 0"/>'
            '<axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint></robot>')


def page_objects(html: str) -> dict[str, dict]:
    """meshcat path -> object of every set_object command of a page."""
    block = html.split("const commands = [", 1)[1].split("];", 1)[0]
    cmds = [umsgpack.unpackb(base64.b64decode(b)) for b in re.findall(r'"([A-Za-z0-9+/=]+)"', block)]
    return {c["path"]: c["object"] for c in cmds if c["type"] == "set_object"}


def test_meshes_resolved_and_placed_where_the_link_is():
    """STL relative to the URDF's folder, OBJ through package://; each drawn box's corners are the file's
    box scaled, placed by the visual origin and the link's pose (Pinocchio's forward kinematics)."""
    mechanism = from_urdf(arm("box.stl", "package://meshes/box.obj"), name="arm")
    with warnings.catch_warnings():
        warnings.simplefilter("error", MissingMesh)
        drawing = Drawing(mechanism, meshes=MeshSearch.of(MESHES, [MESHES.parent]))
    parts = {p.path: p for p in drawing.parts}
    assert parts["links/a_0"].shape.mesh_format == "stl"
    assert parts["links/b_0"].shape.mesh_format == "obj"
    q = np.array([0.7, -0.5])
    model, data = mechanism.model, mechanism.model.createData()
    pin.forwardKinematics(model, data, q)
    local = pin.SE3(pin.rpy.rpyToMatrix(0, 0, 0.4), ORIGIN)
    placements = dict(zip((p.path for p in drawing.parts), drawing.placements(q)))
    for link, joint in (("a", "j1"), ("b", "j2")):
        pose = data.oMi[model.getJointId(joint)] * local
        expected = (BOX * SCALE) @ pose.rotation.T + pose.translation
        corners = parts[f"links/{link}_0"].corners(placements[f"links/{link}_0"])
        assert np.allclose(np.sort(corners, axis=0), np.sort(expected, axis=0), atol=1e-12)


def test_snapshot_page_carries_the_mesh_files():
    html = snapshot(from_urdf(arm("box.stl", "box.obj"), name="arm"), meshes=MeshSearch.of(MESHES))
    objects = page_objects(html)
    formats = {path.rsplit("/", 1)[-1]: obj["geometries"][0].get("format") for path, obj in objects.items()
               if "/links/" in path}
    assert formats == {"a_0": "stl", "b_0": "obj"}
    stl = next(o for p, o in objects.items() if p.endswith("links/a_0"))["geometries"][0]["data"]
    assert stl.data == (MESHES / "box.stl").read_bytes()


def test_missing_mesh_is_a_warning_and_a_placeholder():
    mechanism = from_urdf(arm("box.stl", "package://elsewhere/gone.stl"), name="arm")
    with pytest.warns(MissingMesh, match=r"link 'b'.*gone\.stl.*not found"):
        drawing = Drawing(mechanism, meshes=MeshSearch.of(MESHES))
    parts = {p.path: p for p in drawing.parts}
    assert parts["links/a_0"].shape.mesh_format == "stl"
    assert type(parts["links/b_0"].shape).__name__ == "Sphere" and parts["links/b_0"].rgba == MISSING
    with pytest.warns(MissingMesh):  # without the URDF's folder, the relative name is not found either
        html = snapshot(mechanism)
    assert len([p for p in page_objects(html) if "/links/" in p]) == 3  # two placeholders, a bar from a to b


def test_search_order():
    """Absolute names as they are; relative: the URDF's folder first; package://: DIR/PKG/..., then DIR/..."""
    search = MeshSearch.of(MESHES, [MESHES.parent, MESHES])
    assert search.resolve(str(MESHES / "box.stl")) == MESHES / "box.stl"
    assert search.resolve("box.stl") == MESHES / "box.stl"
    assert search.resolve("meshes/box.obj") == MESHES / "box.obj"  # found in the search path
    assert search.resolve("package://meshes/box.obj") == MESHES / "box.obj"
    assert search.resolve("package://any_name/box.stl") == MESHES / "box.stl"  # a folder that is the package
    assert search.resolve("package://meshes/gone.stl") is None
    assert MeshSearch().resolve("box.stl") is None


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
