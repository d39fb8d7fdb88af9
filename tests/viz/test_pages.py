"""`mechkit.viz.pages`: a pose, an animated scene and a scene's poses overlaid as self-contained pages
(decoded command by command, and shown in a real browser where Chromium is present); `mechkit
snapshot`'s library side."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit import scenes, viz
from mechkit.base.exceptions import InvalidParameters, MechkitError, MethodUnavailable
from mechkit.viz import drawing, meshcat_page
from mechkit.viz.browser import screenshot

from .in_browser import assert_shows_a_mechanism, needs_browser
from .meshcat_pages import commands, objects


def test_snapshot_marks_actuators_cuts_and_ground(load_cached):
    m = load_cached("five_bar")
    cmds = commands(viz.snapshot(m))
    colours = objects(cmds)
    red = {p for p, c in colours.items() if c == meshcat_page._hex(drawing.ACTUATED)}
    assert red == {f"/mechanism/pose/joints/{j}" for j in m.actuated}
    cuts = {p for p in colours if "/cuts/" in p}
    assert cuts == {f"/mechanism/pose/cuts/{c.name}" for c in m.closures}
    assert all(colours[p] == meshcat_page._hex(drawing.CUT) for p in cuts)
    ground = [p for p in colours if "/ground/" in p]
    assert len([p for p in ground if "anchor" in p]) == 2 and len([p for p in ground if "bar" in p]) == 1
    links = [p for p in colours if "/links/" in p]
    assert len(links) == 4 and len({colours[p] for p in links}) == 4  # one colour per link, from the URDF
    assert any(c["type"] == "set_property" and c["property"] == "fov" for c in cmds)


def test_animation_tracks_follow_each_pose(load_cached):
    m = load_cached("five_bar")
    poses = scenes.scene_poses(m, "sweep")
    cmds = commands(viz.animation(m, "sweep"))
    (anim,) = [c for c in cmds if c["type"] == "set_animation"]
    assert anim["options"]["loopMode"] == 2202 and anim["options"]["repetitions"] == math.inf
    clips = {a["path"]: a["clip"] for a in anim["animations"]}
    elbow = m.model.names[2]  # a joint that moves (the one at a support only turns about its fixed axis)
    visual = pin.buildGeomFromUrdfString(m.model, m.urdf, pin.GeometryType.VISUAL)
    k = next(i for i, g in enumerate(visual.geometryObjects) if g.parentJoint == 1)
    assert type(visual.geometryObjects[k].geometry).__name__ == "Box"  # drawn without a local rotation
    clip = clips[f"/mechanism/pose/links/{visual.geometryObjects[k].name}"]
    tracks = {t["name"]: t["keys"] for t in clip["tracks"]}
    assert len(tracks[".position"]) == len(poses) and 4 <= len(poses) / clip["fps"] <= 12
    vdata = visual.createData()
    for i in (0, len(poses) // 3, len(poses) - 1):
        pin.updateGeometryPlacements(m.model, m.model.createData(), visual, vdata, poses[i])
        assert tracks[".position"][i]["time"] == i
        assert np.allclose(tracks[".position"][i]["value"], vdata.oMg[k].translation, atol=1e-12)
        x, y, z, w = tracks[".quaternion"][i]["value"]  # three.js order
        assert np.allclose(pin.Quaternion(w, x, y, z).toRotationMatrix(), vdata.oMg[k].rotation, atol=1e-12)
    assert f"/mechanism/pose/joints/{elbow}" in clips  # markers move too
    assert not [p for p in clips if "/ground/" in p]  # the ground does not


def test_overlay_shows_ghosts_and_the_last_pose(load_cached):
    m = load_cached("five_bar")
    colours = objects(commands(viz.overlay(m, "sweep", ghosts=3)))
    assert len([p for p in colours if p.startswith("/mechanism/pose/links/")]) == 4
    # the sweep ends where it starts: the first ghost would sit on the last pose and is left out
    assert {p.split("/")[2] for p in colours if "ghost" in p} == {"ghost0", "ghost1"}


def test_snapshot_command_errors(load_cached, tmp_path, monkeypatch):
    m = load_cached("four_bar")
    with pytest.raises(MechkitError, match="give -o"):
        viz.snapshot_command(m)
    with pytest.raises(InvalidParameters, match="not both"):
        viz.snapshot_command(m, q=[0.5], scene="sweep", html=str(tmp_path / "a.html"))
    monkeypatch.delenv("MECHKIT_CHROMIUM", raising=False)
    monkeypatch.setenv("PATH", str(tmp_path))
    with pytest.raises(MethodUnavailable, match="Chromium browser, not found.*apt-get install chromium"):
        viz.snapshot_command(m, html=str(tmp_path / "a.html"), png=str(tmp_path / "a.png"))
    assert not list(tmp_path.iterdir())  # nothing written
    monkeypatch.setenv("MECHKIT_CHROMIUM", str(tmp_path / "my-chromium"))
    with pytest.raises(MethodUnavailable, match="MECHKIT_CHROMIUM=.*my-chromium.* is not an executable"):
        viz.snapshot_command(m, png=str(tmp_path / "a.png"))


def test_pose_from_the_command_line(load_cached, tmp_path, capsys):
    m = load_cached("four_bar")
    (path,) = viz.snapshot_command(m, q=[1.3], html=str(tmp_path / "p.html"))
    crank = next(
        c
        for c in commands(path.read_text())
        if c.get("path") == "/mechanism/pose/joints/coupler" and c["type"] == "set_transform"
    )
    q = m.assemble([1.3], guess=m.home_q)
    data = m.model.createData()
    pin.forwardKinematics(m.model, data, q)
    coupler = m.model.getJointId("coupler")
    assert np.allclose(crank["matrix"][12:15], data.oMi[coupler].translation, atol=1e-12)
    assert capsys.readouterr().out == ""  # library code prints nothing


def test_mechanism_scene_box_holds_every_joint(load_cached):
    m = load_cached("ten_bar")
    _, lo, hi = viz.mechanism_scene(m, m.home_q)
    data = m.model.createData()
    pin.forwardKinematics(m.model, data, m.home_q)
    origins = np.array([data.oMi[j].translation for j in range(1, m.model.njoints)])
    assert np.all(origins >= lo) and np.all(origins <= hi)


@needs_browser
def test_animation_plays(load_cached, tmp_path):
    """The animated page moves: two screenshots at different times differ, each showing the mechanism."""
    page = tmp_path / "sweep.html"
    viz.animation(load_cached("five_bar"), "sweep", page)
    early, late = (
        screenshot(page, tmp_path / "early.png", budget_ms=300),
        screenshot(page, tmp_path / "late.png", budget_ms=2500),
    )
    assert_shows_a_mechanism(early)
    assert_shows_a_mechanism(late)
    from PIL import Image, ImageChops

    with Image.open(early) as a, Image.open(late) as b:
        changed = np.asarray(ImageChops.difference(a.convert("RGB"), b.convert("RGB")).convert("L")) > 12
        assert changed.mean() > 0.002


@needs_browser
@pytest.mark.slow
@pytest.mark.parametrize("name", list(mechkit.specs()))
def test_every_scene_picture_shows_the_mechanism(name, tmp_path):
    m = mechkit.load(name)
    for scene in scenes.scenes(m):
        png = tmp_path / f"{scene}.png"
        viz.snapshot_command(m, scene=scene, html=str(tmp_path / f"{scene}.html"), png=str(png))
        assert_shows_a_mechanism(png)
