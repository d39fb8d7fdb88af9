"""`mechkit.viz.meshes`: URDF mesh visuals found relative to the file and through package:// with a
search path, drawn where the link is (scale and origin applied; in a real browser where Chromium is
present); a missing mesh is a warning and a placeholder."""

from __future__ import annotations

import warnings

import numpy as np
import pinocchio as pin
import pytest

from mechkit import from_urdf
from mechkit.viz import Drawing, snapshot
from mechkit.viz.browser import screenshot
from mechkit.viz.meshes import MISSING, MeshSearch, MissingMesh

from .in_browser import assert_framed, drawn_pixels, needs_browser
from .mesh_urdf import BOX, MESHES, ORIGIN, SCALE, arm
from .meshcat_pages import page_objects


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
    formats = {
        path.rsplit("/", 1)[-1]: obj["geometries"][0].get("format")
        for path, obj in objects.items()
        if "/links/" in path
    }
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


@needs_browser
def test_mesh_drawing_in_a_real_browser(tmp_path):
    """A URDF drawn only by mesh visuals (STL and OBJ fixtures) shows them, framed."""
    page = tmp_path / "arm.html"
    snapshot(
        from_urdf(arm("box.stl", "box.obj"), name="arm"), np.array([0.7, -0.5]), page, meshes=MeshSearch.of(MESHES)
    )
    mask = drawn_pixels(screenshot(page, tmp_path / "arm.png"))
    assert_framed(mask)
