"""Meshcat pictures of a mechanism: self-contained HTML of a pose, of an animated scene, or of a scene's
poses overlaid; drawn with primitives only.

The page holds meshcat's viewer script and every drawing command (msgpack, base64): it opens offline,
no meshcat server is started. Links are the URDF visual primitives in their URDF colours (a palette per
limb when the URDF gives none); joints are short cylinders along their axis, actuated ones red and
thicker; loop cuts are yellow spheres; the ground is grey (anchors at the supports, joined by bars when
the URDF draws no ground body). The camera is fitted to the drawn primitives (the drawing is centred
on the origin, which meshcat orbits).

Scenes come from `mechkit.scenes` (the spec's own, plus the generic input sweep). The camera looks
along the spec's `view` (world direction from the mechanism to the camera), else along the thin axis
of a flat mechanism, else obliquely. Animations play the poses at an even pace (at most MAX_FRAMES of them, evenly picked), ping-pong,
4 to 12 s per pass whatever the scene's own duration (meshcat's controls change the speed).

Nothing here prints or opens a window; screenshots (`--png`) are an explicit call to `mechkit.browser`.
"""

from __future__ import annotations

import base64
import math
import os
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pinocchio as pin

from mechkit.atomic import write_text
from mechkit.exceptions import InvalidParameters, MechkitError
from mechkit.mechanism import Mechanism
from mechkit.scenes import joint_extent, scene_poses

BACKGROUND = (0.93, 0.95, 0.97)  # uniform page background (rgb 0..1)
ACTUATED = (0.85, 0.08, 0.08, 1.0)
PASSIVE = (0.15, 0.15, 0.18, 1.0)
CUT = (1.0, 0.78, 0.0, 1.0)
GROUND = (0.3, 0.3, 0.32, 1.0)
LIMB_PALETTE = ((0.85, 0.33, 0.1), (0.2, 0.45, 0.8), (0.3, 0.65, 0.3), (0.6, 0.4, 0.7), (0.9, 0.6, 0.15),
                (0.25, 0.65, 0.7))
GHOST_OPACITY = 0.22
FOV_DEG = 30.0  # vertical field of view of the camera
ASPECT = 4 / 3  # narrowest width/height the framing allows for
MARGIN = 0.08  # fraction of the view kept free around the mechanism
MAX_FRAMES = 240  # poses kept in an animation (the page grows with frames x parts)
_LOOP_PINGPONG = 2202  # THREE.LoopPingPong


def _meshcat():
    try:
        import umsgpack
        from meshcat import animation, commands, geometry
        from meshcat.path import Path as MeshcatPath
    except ImportError:
        raise MechkitError("snapshots need meshcat: pip install 'mechkit[viz]'") from None
    return geometry, umsgpack, commands, animation, MeshcatPath


def _hex(rgba: Sequence[float]) -> int:
    r, g, b = (round(255 * float(c)) for c in rgba[:3])
    return (r << 16) + (g << 8) + b


class StaticScene:
    """An ordered list of meshcat commands that becomes one self-contained HTML page."""

    def __init__(self) -> None:
        self.geometry, self._umsgpack, self._commands_module, self._animation, self._MeshcatPath = _meshcat()
        self._commands: list[bytes] = []

    def _send(self, lowered: dict) -> None:
        self._commands.append(self._umsgpack.packb(lowered))

    def _path(self, path: str):
        return self._MeshcatPath(tuple(p for p in path.split("/") if p))

    def add(self, path: str, shape, rgba: Sequence[float], transform: np.ndarray) -> None:
        """Add a meshcat primitive at `path` with a colour (rgba 0..1) and a 4x4 world transform (m)."""
        material = self.geometry.MeshPhongMaterial(color=_hex(rgba), opacity=float(rgba[3]),
                                                   transparent=bool(rgba[3] < 1))
        self._send(self._commands_module.SetObject(shape, material, self._path(path)).lower())
        self.set_transform(path, transform)

    def set_transform(self, path: str, transform: np.ndarray) -> None:
        self._send(self._commands_module.SetTransform(np.asarray(transform, dtype=float), self._path(path)).lower())

    def set_property(self, path: str, key: str, value) -> None:
        self._send(self._commands_module.SetProperty(key, value, self._path(path)).lower())

    def set_background(self, rgb: Sequence[float] = BACKGROUND) -> None:
        """A uniform background colour (rgb 0..1); also hides meshcat's grid and axes."""
        for key in ("top_color", "bottom_color"):
            self.set_property("/Background", key, [float(c) for c in rgb])
        self.set_property("/Grid", "visible", False)
        self.set_property("/Axes", "visible", False)

    def frame_camera(self, points: np.ndarray, root: str = "/mechanism",
                     direction: Sequence[float] = (1.0, -1.6, 0.9)) -> None:
        """Centre the drawing under `root` on the origin and place the camera so every point is in view.

        Args:
            points: (N, 3) world points (m) to keep in view, e.g. the corners of every drawn primitive.
            root: meshcat path of the drawing (translated so the points' bounding box is centred on the
                origin, which meshcat's camera orbits).
            direction: world direction from the mechanism to the camera (z is up).
        """
        pts = np.atleast_2d(np.asarray(points, dtype=float))
        centre = (pts.min(axis=0) + pts.max(axis=0)) / 2
        distance, back = camera_distance(pts - centre, direction)
        self.set_transform(root, pin.SE3(np.eye(3), -centre).homogeneous)
        position = back * distance
        camera = "/Cameras/default/rotated/<object>"
        # the camera lives in meshcat's y-up "rotated" frame: world (x, y, z) -> (x, z, -y)
        self.set_property(camera, "position", [position[0], position[2], -position[1]])
        self.set_property(camera, "fov", FOV_DEG)
        self.set_property(camera, "near", distance / 100)
        self.set_property(camera, "far", distance * 20)

    def set_animation(self, tracks: dict[str, Sequence[np.ndarray]], fps: float) -> None:
        """Animate objects: `tracks` maps a meshcat path to its 4x4 world transforms, one per frame.

        Lowered from `meshcat.animation.Animation` into one set_animation command that plays at
        `fps` frames per second, ping-pong, forever.
        """
        animation = self._animation.Animation(default_framerate=fps)
        for path, transforms in tracks.items():
            target = self._path(path)
            for frame, transform in enumerate(transforms):
                self._animation.AnimationFrameVisualizer(animation, target, frame).set_transform(transform)
        lowered = self._commands_module.SetAnimation(animation, play=True, repetitions=math.inf).lower()
        lowered["options"]["loopMode"] = _LOOP_PINGPONG
        self._send(lowered)

    def html(self, title: str = "mechkit", caption: str = "") -> str:
        """The page: meshcat's viewer script inlined, then every command. Opened with `#capture` in its
        address, the page hides the controls and the caption (for screenshots)."""
        import html as html_escape

        import meshcat

        script = (Path(meshcat.__file__).parent / "viewer" / "dist" / "main.min.js").read_text()
        blobs = ",\n".join(f'"{base64.b64encode(c).decode()}"' for c in self._commands)
        return f"""<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>{html_escape.escape(title)}</title>
<style>body {{margin: 0}} #meshcat-pane {{width: 100vw; height: 100vh; overflow: hidden}}
#caption {{position: absolute; left: 8px; bottom: 8px; font: 13px sans-serif; color: #333}}
.capture .dg, .capture #caption {{display: none}}</style></head>
<body><div id="meshcat-pane"></div><div id="caption">{html_escape.escape(caption)}</div>
<script>{script}</script>
<script>
if (location.hash.includes("capture")) document.body.classList.add("capture");
var viewer = new MeshCat.Viewer(document.getElementById("meshcat-pane"));
const commands = [
{blobs}
];
for (const blob of commands) {{
  viewer.handle_command_bytearray(Uint8Array.from(atob(blob), c => c.charCodeAt(0)));
}}
</script></body></html>
"""


def camera_distance(points: np.ndarray, direction: Sequence[float]) -> tuple[float, np.ndarray]:
    """Distance from the origin along `direction` at which a camera looking at the origin sees every point.

    Args:
        points: (N, 3) world points (m), relative to the orbit centre.
        direction: world direction from the centre to the camera (z up).

    Returns:
        (distance in m, unit direction).
    """
    back = np.asarray(direction, dtype=float)
    back = back / np.linalg.norm(back)
    right = np.cross(-back, [0.0, 0.0, 1.0])
    if np.linalg.norm(right) < 1e-9:  # looking straight down or up: any horizontal right will do
        right = np.array([1.0, 0.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, -back)
    tan_v = math.tan(math.radians(FOV_DEG) / 2) * (1 - MARGIN)
    tan_h = tan_v * ASPECT
    depth = points @ back  # towards the camera
    need = np.maximum(np.abs(points @ up) / tan_v, np.abs(points @ right) / tan_h) + depth
    extent = float(np.max(np.ptp(points, axis=0))) if len(points) > 1 else 0.0
    return max(float(need.max()), float(depth.max()) + 0.05 * extent, 1e-3), back  # never inside the drawing


@dataclass(frozen=True)
class Part:
    """One drawn primitive: meshcat path (relative to the drawing's root), shape, colour, half sizes."""

    path: str
    shape: object
    rgba: tuple[float, float, float, float]
    half_extent: np.ndarray  # in the primitive's own frame (m)

    def corners(self, placement: np.ndarray) -> np.ndarray:
        """The 8 corners of the primitive's box at a 4x4 world placement."""
        signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
        return (signs * self.half_extent) @ placement[:3, :3].T + placement[:3, 3]


class Drawing:
    """What is drawn of one mechanism, and where each part sits at any configuration.

    Args:
        mechanism: the mechanism.
        size: marker scale (m); default: the extent of the joint origins at its home configuration.
    """

    def __init__(self, mechanism: Mechanism, size: float | None = None):
        self.mechanism = mechanism
        model = mechanism.model
        self.model, self.data = model, model.createData()
        self.visual = pin.buildGeomFromUrdfString(model, mechanism.urdf, pin.GeometryType.VISUAL)
        self.vdata = self.visual.createData()
        g = StaticScene().geometry
        self.size = joint_extent(model, self.data, mechanism.home_q) if size is None else float(size)
        s = self.size
        self.parts: list[Part] = []
        self._links: list[tuple[int, np.ndarray]] = []  # (geometry index, local rotation)
        colours = _link_colours(model, self.visual)
        for k, obj in enumerate(self.visual.geometryObjects):
            primitive = _shape(g, obj.geometry)
            if primitive is not None:
                shape, local, half = primitive
                self.parts.append(Part(f"links/{obj.name}", shape, colours[k], half))
                self._links.append((k, local))
        self._joints: list[tuple[int, np.ndarray | None]] = []
        actuated = set(mechanism.actuated)
        axes = _local_axes(model, self.data)
        for j in range(1, model.njoints):
            name = model.names[j]
            big = name in actuated
            colour = ACTUATED if big else PASSIVE
            if axes[j] is not None:
                r, length = (0.022, 0.08) if big else (0.013, 0.055)
                shape, half = g.Cylinder(length * s, r * s), np.array([r, length / 2, r]) * s
            else:
                r = 0.03 if big else 0.022
                shape, half = g.Sphere(r * s), np.full(3, r * s)
            self.parts.append(Part(f"joints/{name}", shape, colour, half))
            self._joints.append((j, axes[j]))
        self._cuts = [model.getFrameId(c.frame_b) for c in mechanism.closures]
        for closure in mechanism.closures:
            self.parts.append(Part(f"cuts/{closure.name}", g.Sphere(0.028 * s), CUT, np.full(3, 0.028 * s)))
        self._ground = self._ground_parts(g)
        self.parts.extend(part for part, _ in self._ground)

    def _ground_parts(self, g) -> list[tuple[Part, np.ndarray]]:
        """Grey anchors under the supports (joints on the ground), joined by bars (a minimum spanning tree)
        unless the URDF draws a ground body itself; all fixed in the world."""
        model, s = self.model, self.size
        supports = np.array([model.jointPlacements[j].translation for j in range(1, model.njoints)
                             if model.parents[j] == 0])
        if len(supports) == 0:
            return []
        centre_z = (supports[:, 2].min() + supports[:, 2].max()) / 2
        side = 0.06 * s
        out = []
        for i, p in enumerate(np.unique(np.round(supports, 9), axis=0)):
            below = -1.0 if p[2] <= centre_z + 1e-9 else 1.0  # anchors sit on the outer side of the supports
            centre = p + np.array([0.0, 0.0, below * side / 2])
            out.append((Part(f"ground/anchor{i}", g.Box([side] * 3), GROUND, np.full(3, side / 2)),
                        pin.SE3(np.eye(3), centre).homogeneous))
        drawn = any(obj.parentJoint == 0 for obj in self.visual.geometryObjects)
        if drawn:
            return out
        anchors = np.array([placement[:3, 3] for _, placement in out])
        for i, (a, b) in enumerate(_spanning_tree(anchors)):
            d = anchors[b] - anchors[a]
            thick = 0.025 * s
            half = np.array([thick, np.linalg.norm(d) / 2, thick / 2])
            rotation = _rotation_y_to(d)
            out.append((Part(f"ground/bar{i}", g.Box(list(2 * half)), GROUND, half),
                        pin.SE3(rotation, (anchors[a] + anchors[b]) / 2).homogeneous))
        return out

    def placements(self, q: np.ndarray) -> list[np.ndarray]:
        """4x4 world placement (m) of every part at q, in the order of `parts`."""
        model, data = self.model, self.data
        pin.framesForwardKinematics(model, data, q)
        pin.updateGeometryPlacements(model, data, self.visual, self.vdata)
        out = [(self.vdata.oMg[k] * pin.SE3(local, np.zeros(3))).homogeneous for k, local in self._links]
        for j, axis in self._joints:
            oMi = data.oMi[j]
            rotation = np.eye(3) if axis is None else _rotation_y_to(oMi.rotation @ axis)
            out.append(pin.SE3(rotation, oMi.translation).homogeneous)
        out.extend(pin.SE3(np.eye(3), data.oMf[f].translation).homogeneous for f in self._cuts)
        out.extend(placement for _, placement in self._ground)
        return out

    def corners(self, q: np.ndarray) -> np.ndarray:
        """Corners of every drawn primitive at q (world, m), for framing."""
        return np.vstack([part.corners(T) for part, T in zip(self.parts, self.placements(q))])

    def draw(self, scene: StaticScene, q: np.ndarray, prefix: str = "/mechanism", ghost: bool = False) -> None:
        """Add every part at q under `prefix`; a ghost is the links only, faded."""
        for part, placement in zip(self.parts, self.placements(q)):
            if ghost and not part.path.startswith("links/"):
                continue
            rgba = (*part.rgba[:3], GHOST_OPACITY) if ghost else part.rgba
            scene.add(f"{prefix}/{part.path}", part.shape, rgba, placement)

    def view(self) -> tuple[float, float, float]:
        """The camera direction: the spec's view, else nearly face-on to a planar linkage (its joint origins
        at home span a thin slab), else oblique."""
        if self.mechanism.spec.view is not None:
            return self.mechanism.spec.view
        model, data = self.model, self.data
        pin.forwardKinematics(model, data, self.mechanism.home_q)
        extent = np.ptp([data.oMi[j].translation for j in range(1, model.njoints)], axis=0)
        thin = int(np.argmin(extent))
        if extent[thin] < 0.3 * extent.max():
            return ((1.0, 0.2, 0.12), (0.2, -1.0, 0.12), (0.2, -0.3, 1.0))[thin]  # nearly face-on
        return (1.0, -1.6, 0.9)


def _link_colours(model: pin.Model, visual: pin.GeometryModel) -> list[tuple[float, float, float, float]]:
    """URDF colours; when the moving links all share one colour, a palette colour per limb (the subtree of
    one support joint)."""
    colours = [tuple(float(c) for c in obj.meshColor) for obj in visual.geometryObjects]
    moving = {colours[k] for k, obj in enumerate(visual.geometryObjects) if obj.parentJoint != 0}
    if len(moving) > 1:
        return colours
    supports = [j for j in range(1, model.njoints) if model.parents[j] == 0]
    for k, obj in enumerate(visual.geometryObjects):
        j = obj.parentJoint
        if j == 0:
            colours[k] = GROUND
            continue
        while model.parents[j] != 0:
            j = model.parents[j]
        colours[k] = (*LIMB_PALETTE[supports.index(j) % len(LIMB_PALETTE)], colours[k][3])
    return colours


def _shape(g, geometry) -> tuple[object, np.ndarray, np.ndarray] | None:
    """Meshcat primitive for a coal shape, the local rotation that aligns it (meshcat cylinders lie along
    y, coal's along z) and its half sizes in meshcat's frame; None for meshes (not drawn)."""
    name = type(geometry).__name__
    if name == "Box":
        half = np.asarray(geometry.halfSide, dtype=float)
        return g.Box(list(2 * half)), np.eye(3), half
    if name == "Sphere":
        r = float(geometry.radius)
        return g.Sphere(r), np.eye(3), np.full(3, r)
    if name == "Cylinder":
        r, h = float(geometry.radius), float(geometry.halfLength)
        return g.Cylinder(2 * h, r), pin.rpy.rpyToMatrix(np.pi / 2, 0, 0), np.array([r, h, r])
    return None


def _local_axes(model: pin.Model, data: pin.Data) -> list[np.ndarray | None]:
    """Axis of each one-coordinate joint in its own frame (rotation axis, or translation for prismatic);
    None for the universe and for multi-coordinate joints."""
    pin.computeJointJacobians(model, data, pin.neutral(model))
    axes: list[np.ndarray | None] = [None]
    for j in range(1, model.njoints):
        joint = model.joints[j]
        if joint.nv != 1:
            axes.append(None)
            continue
        col = pin.getJointJacobian(model, data, j, pin.ReferenceFrame.LOCAL)[:, joint.idx_v]
        vec = col[3:] if np.linalg.norm(col[3:]) > 1e-12 else col[:3]
        axes.append(vec / np.linalg.norm(vec))
    return axes


def _rotation_y_to(direction: np.ndarray) -> np.ndarray:
    """A rotation taking +y onto `direction` (meshcat cylinders lie along y)."""
    y = np.array([0.0, 1.0, 0.0])
    d = direction / np.linalg.norm(direction)
    v, c = np.cross(y, d), float(y @ d)
    if np.linalg.norm(v) < 1e-12:
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    K = pin.skew(v)
    return np.eye(3) + K + K @ K / (1 + c)


def _spanning_tree(points: np.ndarray) -> list[tuple[int, int]]:
    """Edges of a minimum spanning tree of the points (Prim)."""
    edges, inside = [], [0]
    while len(inside) < len(points):
        d = np.linalg.norm(points[inside][:, None, :] - points[None, :, :], axis=2)
        d[:, inside] = np.inf
        a, b = np.unravel_index(np.argmin(d), d.shape)
        edges.append((inside[a], int(b)))
        inside.append(int(b))
    return edges


# ---------------------------------------------------------------- pages
def _page(mechanism: Mechanism, poses: Sequence[np.ndarray], *, animate: bool = False, ghosts: int = 0,
          caption: str = "") -> str:
    """HTML of the mechanism: at poses[-1] (with `ghosts` faded earlier poses), or animated along poses."""
    drawing = Drawing(mechanism)
    scene = StaticScene()
    scene.set_background()
    if animate:
        shown = [poses[int(i)] for i in np.linspace(0, len(poses) - 1, min(len(poses), MAX_FRAMES)).round()]
        drawing.draw(scene, shown[0], "/mechanism/pose")
    else:  # ghosts evenly spread from the first pose, then the last pose (periodic scenes: no ghost on it)
        picks = [poses[int(i)] for i in np.linspace(0, len(poses) - 1, ghosts + 1).round()] if ghosts else []
        shown = [q for q in picks[:-1] if np.max(np.abs(q - poses[-1])) > 1e-9] + [poses[-1]]
        for i, q in enumerate(shown[:-1]):
            drawing.draw(scene, q, f"/mechanism/ghost{i}", ghost=True)
        drawing.draw(scene, shown[-1], "/mechanism/pose")
    points = np.vstack([drawing.corners(q) for q in shown])
    scene.frame_camera(points, "/mechanism", drawing.view())
    if animate:
        frames = [drawing.placements(q) for q in shown]
        tracks = {}
        for k, part in enumerate(drawing.parts):
            path = [frame[k] for frame in frames]
            if max(float(np.max(np.abs(T - path[0]))) for T in path) > 1e-12:  # fixed parts need no track
                tracks[f"/mechanism/pose/{part.path}"] = path
        fps = len(shown) / min(max(len(shown) / 30, 4.0), 12.0)
        scene.set_animation(tracks, fps)
    return scene.html(mechanism.spec.name, caption)


def mechanism_scene(mechanism: Mechanism, q: np.ndarray, prefix: str = "/mechanism",
                    scene: StaticScene | None = None) -> tuple[StaticScene, np.ndarray, np.ndarray]:
    """Draw a mechanism at q into a scene (new one by default).

    Returns:
        (scene, lower corner, upper corner) of the drawn primitives (world, m).
    """
    scene = scene or StaticScene()
    drawing = Drawing(mechanism)
    drawing.draw(scene, q, prefix)
    corners = drawing.corners(q)
    return scene, corners.min(axis=0), corners.max(axis=0)


def snapshot(mechanism: Mechanism, q: np.ndarray | None = None, path: str | os.PathLike | None = None) -> str:
    """Self-contained HTML of the mechanism at q (default: its home assembly); written to `path` if given."""
    q = mechanism.home_q if q is None else np.asarray(q, dtype=float)
    html = _page(mechanism, [q], caption=f"{mechanism.spec.name}: {mechanism.spec.summary}")
    if path is not None:
        write_text(path, html)
    return html


def animation(mechanism: Mechanism, scene: str, path: str | os.PathLike | None = None, *,
              poses: Sequence[np.ndarray] | None = None) -> str:
    """Self-contained HTML animating one of the mechanism's scenes; written to `path` if given.
    `poses`: the scene's poses when already computed (by `scene_poses`)."""
    poses = scene_poses(mechanism, scene) if poses is None else poses
    html = _page(mechanism, poses, animate=True, caption=f"{mechanism.spec.name}, scene {scene!r}: "
                                                          f"{len(poses)} poses")
    if path is not None:
        write_text(path, html)
    return html


def overlay(mechanism: Mechanism, scene: str, ghosts: int = 3, path: str | os.PathLike | None = None, *,
            poses: Sequence[np.ndarray] | None = None) -> str:
    """Self-contained HTML of a scene as one picture: its last pose, and `ghosts` earlier poses (evenly
    spread from the first) faded; written to `path` if given. `poses`: as for `animation`."""
    poses = scene_poses(mechanism, scene) if poses is None else poses
    html = _page(mechanism, poses, ghosts=ghosts, caption=f"{mechanism.spec.name}, scene {scene!r}")
    if path is not None:
        write_text(path, html)
    return html


def snapshot_command(mechanism: Mechanism, q: str | None = None, scene: str | None = None,
                     html: str | None = None, png: str | None = None) -> list[Path]:
    """What `mechkit snapshot` does: the HTML of a pose (inputs `q`, comma-separated, in actuated order)
    or of an animated scene, and optionally a PNG screenshot (of the pose; of a scene, its overlay
    picture). Returns the files written."""
    if html is None and png is None:
        raise MechkitError("give -o FILE.html, --png FILE.png, or both")
    if q is not None and scene is not None:
        raise InvalidParameters("q", q, "give either --q (one pose) or --scene (an animation), not both")
    if png is not None:
        from mechkit.browser import find_chromium, screenshot

        find_chromium()  # fail before any work when there is no browser
    written: list[Path] = []
    if scene is not None:
        poses = scene_poses(mechanism, scene)
        if html is not None:
            animation(mechanism, scene, html, poses=poses)
            written.append(Path(html))
        page = overlay(mechanism, scene, poses=poses) if png is not None else None
    else:
        pose = None if q is None else mechanism.assemble(_parse_inputs(q), guess=mechanism.home_q)
        page = snapshot(mechanism, pose, html)
        if html is not None:
            written.append(Path(html))
    if png is not None:
        with tempfile.TemporaryDirectory(prefix="mechkit-snapshot-") as tmp:
            source = Path(html) if html is not None and scene is None else write_text(Path(tmp) / "page.html", page)
            written.append(screenshot(source, png))
    return written


def _parse_inputs(text: str) -> list[float]:
    try:
        return [float(x) for x in text.split(",")]
    except ValueError:
        raise InvalidParameters("q", text, "expected numbers separated by commas (rad or m)") from None


def side_by_side(mechanism: Mechanism, poses: Sequence[np.ndarray], path: str | os.PathLike | None = None,
                 caption: str = "") -> str:
    """Self-contained HTML of several configurations drawn next to each other along world x (e.g. every
    assembly of one set of inputs); written to `path` if given."""
    if len(poses) < 1:
        raise InvalidParameters("poses", len(poses), "need at least one configuration")
    drawing = Drawing(mechanism)
    scene = StaticScene()
    scene.set_background()
    corners = [drawing.corners(np.asarray(q, dtype=float)) for q in poses]
    gap = 0.25 * max(float(np.ptp(c[:, 0])) for c in corners)
    shift, points = 0.0, []
    for i, (q, c) in enumerate(zip(poses, corners)):
        offset = np.array([shift - c[:, 0].min(), 0.0, 0.0])
        drawing.draw(scene, np.asarray(q, dtype=float), f"/mechanism/pose{i}")
        scene.set_transform(f"/mechanism/pose{i}", pin.SE3(np.eye(3), offset).homogeneous)
        points.append(c + offset)
        shift += float(np.ptp(c[:, 0])) + gap
    # frame_camera moves /mechanism itself, so the per-pose offsets above stay under it
    scene.frame_camera(np.vstack(points), "/mechanism", drawing.view())
    html = scene.html(mechanism.spec.name, caption or f"{mechanism.spec.name}: {len(poses)} configurations")
    if path is not None:
        write_text(path, html)
    return html
