"""Pictures without a browser: the drawing commands, the camera fit, animations and the scenes protocol."""

from __future__ import annotations

import base64
import dataclasses
import math
import re
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit import scenes, viz
from mechkit.base.exceptions import InvalidParameters, MalformedDescription, MechkitError, MethodUnavailable
from mechkit.loading import from_params
from mechkit.viz import camera, drawing, meshcat_page

umsgpack = pytest.importorskip("umsgpack")
ROOT = Path(__file__).resolve().parent.parent


def commands(html: str) -> list[dict]:
    """The meshcat commands a page replays."""
    block = html.split("const commands = [", 1)[1].split("];", 1)[0]
    return [umsgpack.unpackb(base64.b64decode(b)) for b in re.findall(r'"([A-Za-z0-9+/=]+)"', block)]


def objects(cmds: list[dict]) -> dict[str, int]:
    """meshcat path -> colour of every object set."""
    out = {}
    for c in cmds:
        if c["type"] == "set_object":
            materials = c["object"]["materials"]
            out[c["path"]] = materials[0]["color"]
    return out


def test_camera_fit_keeps_every_point_in_view_and_is_tight():
    rng = np.random.default_rng(3)
    for direction in [(1.0, -1.6, 0.9), (0.35, -1.0, 0.35), (0.0, 0.0, 1.0), (-2.0, 0.5, -0.3)]:
        points = rng.normal(size=(50, 3)) * [0.4, 0.1, 1.3]
        distance, back = camera.camera_distance(points, direction)
        eye = back * distance
        forward = -back
        right = np.cross(forward, [0, 0, 1.0])
        right = right / np.linalg.norm(right) if np.linalg.norm(right) > 1e-9 else np.array([1.0, 0, 0])
        up = np.cross(right, forward)
        rel = points - eye
        depth = rel @ forward
        assert np.all(depth > 0)
        tan_v = math.tan(math.radians(camera.FOV_DEG) / 2)
        ratio = np.maximum(np.abs(rel @ up) / tan_v, np.abs(rel @ right) / (tan_v * camera.ASPECT)) / depth
        assert ratio.max() <= 1 - camera.MARGIN + 1e-12  # in view, with the margin
        assert ratio.max() == pytest.approx(1 - camera.MARGIN, rel=1e-9)  # and no farther than needed


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


def test_drawn_poses_agree_with_the_kinematics(load_cached):
    """Joint markers lie along the world joint axes (from the Jacobian); cut markers sit on both frames."""
    m = load_cached("four_bar")
    drawn = viz.Drawing(m)
    q = m.assemble([1.1])
    placements = dict(zip((p.path for p in drawn.parts), drawn.placements(q)))
    data = m.model.createData()
    pin.computeJointJacobians(m.model, data, q)
    pin.framesForwardKinematics(m.model, data, q)
    for j in range(1, m.model.njoints):
        axis = pin.getJointJacobian(m.model, data, j, pin.ReferenceFrame.WORLD)[3:, m.model.joints[j].idx_v]
        T = placements[f"joints/{m.model.names[j]}"]
        assert np.allclose(T[:3, 1], axis / np.linalg.norm(axis), atol=1e-12)
        assert np.allclose(T[:3, 3], data.oMi[j].translation, atol=1e-12)
    for c in m.closures:
        T = placements[f"cuts/{c.name}"]
        for frame in (c.frame_a, c.frame_b):
            assert np.allclose(T[:3, 3], data.oMf[m.model.getFrameId(frame)].translation, atol=1e-10)


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


def test_sweep_moves_each_input_in_turn_and_stays_assembled(load_cached):
    m = load_cached("five_bar")
    poses = scenes.sweep(m, frames=12)
    assert len(poses) == 1 + 12 * len(m.actuated)
    assert np.array_equal(poses[0], m.home_q)
    home = np.array([m.home_q[m.q_index(j)] for j in m.actuated])
    for n, q in enumerate(poses[1:]):
        i, t = divmod(n, 12)
        expected = home.copy()
        expected[i] += scenes.SWEEP_ANGLE * math.sin(2 * math.pi * (t + 1) / 12)
        assert np.allclose([q[m.q_index(j)] for j in m.actuated], expected, atol=1e-12)
        assert np.max(np.abs(m.closure_residual(q))) < 1e-10
    steps = np.abs(np.diff(poses, axis=0)).max()
    assert steps < 3 * scenes.SWEEP_ANGLE * 2 * math.pi / 12  # continuous: no jump to another assembly branch
    assert np.allclose(poses[-1], m.home_q, atol=1e-9)


def test_sweep_stops_at_the_first_pose_that_does_not_assemble(load_cached):
    m = load_cached("five_bar")
    with pytest.warns(scenes.SweepStopped, match=r"sweep of prox1 stops at .* do not assemble"):
        poses = scenes.sweep(m, frames=24, angle=3.0)
    assert 2 <= len(poses) < 1 + 24 * 2
    assert all(np.max(np.abs(m.closure_residual(q))) < 1e-10 for q in poses)
    assert np.allclose(poses[-1], m.home_q)  # each excursion comes back home


def test_scene_protocol(load_cached):
    """The scenes a spec declares come first, in order, then the generic sweep; their poses are checked."""
    four_bar = load_cached("four_bar")
    good = [four_bar.assemble([a]) for a in np.linspace(0.5, 0.9, 5)]
    bad = [good[0], good[1] + 0.1]
    spec = dataclasses.replace(four_bar.spec, scenes={"turn": lambda mech: good, "bad": lambda mech: bad,
                                                      "short": lambda mech: good[:1]})
    m = from_params(spec, four_bar.params)
    assert list(scenes.scenes(m)) == ["turn", "bad", "short", "sweep"]
    assert all(np.array_equal(a, b) for a, b in zip(scenes.scene_poses(m, "turn"), good))
    with pytest.raises(MalformedDescription, match="pose 1 does not close its loops"):
        scenes.scene_poses(m, "bad")
    with pytest.raises(MalformedDescription, match="at least 2 poses"):
        scenes.scene_poses(m, "short")
    with pytest.raises(InvalidParameters, match="turn, bad, short, sweep"):
        scenes.scene_poses(m, "dance")


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
        viz.snapshot_command(m, q="0.5", scene="sweep", html=str(tmp_path / "a.html"))
    with pytest.raises(InvalidParameters, match="numbers separated by commas"):
        viz.snapshot_command(m, q="0.5;1", html=str(tmp_path / "a.html"))
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
    (path,) = viz.snapshot_command(m, q="1.3", html=str(tmp_path / "p.html"))
    crank = next(c for c in commands(path.read_text()) if c.get("path") == "/mechanism/pose/joints/coupler"
                 and c["type"] == "set_transform")
    q = m.assemble([1.3], guess=m.home_q)
    data = m.model.createData()
    pin.forwardKinematics(m.model, data, q)
    coupler = m.model.getJointId("coupler")
    assert np.allclose(crank["matrix"][12:15], data.oMi[coupler].translation, atol=1e-12)
    assert capsys.readouterr().out == ""  # library code prints nothing


@pytest.mark.parametrize("name", list(mechkit.specs()))
def test_gallery_has_the_mechanism(name):
    """The committed gallery agrees with the registry (regenerate with tools/gallery.py)."""
    png = ROOT / "docs" / "gallery" / f"{name}.png"
    assert png.is_file() and png.stat().st_size < 200_000
    rows = [line for line in (ROOT / "docs" / "gallery.md").read_text().splitlines() if line.startswith(f"| `{name}` |")]
    assert len(rows) == 1 and f"(docs/gallery/{name}.png)" in rows[0] and "not drawn yet" not in rows[0]


def test_mechanism_scene_box_holds_every_joint(load_cached):
    m = load_cached("ten_bar")
    _, lo, hi = viz.mechanism_scene(m, m.home_q)
    data = m.model.createData()
    pin.forwardKinematics(m.model, data, m.home_q)
    origins = np.array([data.oMi[j].translation for j in range(1, m.model.njoints)])
    assert np.all(origins >= lo) and np.all(origins <= hi)


def test_one_colour_per_limb_when_the_urdf_gives_none(load_cached):
    m = load_cached("five_bar")
    visual = pin.buildGeomFromUrdfString(m.model, m.urdf, pin.GeometryType.VISUAL)
    for obj in visual.geometryObjects:
        obj.meshColor = np.array([0.9, 0.9, 0.9, 1.0])
    colours = dict(zip((m.model.names[g.parentJoint] for g in visual.geometryObjects),
                       drawing._link_colours(m.model, visual)))
    # five-bar limbs: prox1 -> dist1 and prox2 -> dist2, cut at C
    assert colours["prox1"] == colours["dist1"] != colours["prox2"] == colours["dist2"]
