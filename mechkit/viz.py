"""Meshcat static snapshots: self-contained HTML of a mechanism, drawn with primitives only.

The scene is built as meshcat drawing commands and written with meshcat's viewer JavaScript
inlined, without starting a meshcat server: the file opens offline in any browser. Links are drawn
from the URDF visual primitives; joint axes as thin cylinders (actuated ones red), loop cuts as
yellow spheres, the ground as a grey plate; the camera is framed on the mechanism's bounding box.
"""

from __future__ import annotations

import base64
import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pinocchio as pin

from mechkit.atomic import write_text
from mechkit.exceptions import MechkitError


def _meshcat():
    try:
        import meshcat.geometry as geometry
        import umsgpack
        from meshcat.commands import SetAnimation, SetObject, SetProperty, SetTransform
    except ImportError:
        raise MechkitError("snapshots need meshcat: pip install 'mechkit[viz]'") from None
    return geometry, umsgpack, SetObject, SetTransform, SetProperty, SetAnimation


def _hex(rgba: Sequence[float]) -> int:
    r, g, b = (int(round(255 * float(c))) for c in rgba[:3])
    return (r << 16) + (g << 8) + b


class StaticScene:
    """An ordered list of meshcat commands that becomes one self-contained HTML page."""

    def __init__(self) -> None:
        self.geometry, self._umsgpack, self._SetObject, self._SetTransform, self._SetProperty, self._SetAnimation = _meshcat()
        self._commands: list[bytes] = []

    def _send(self, command) -> None:
        self._commands.append(self._umsgpack.packb(command.lower()))

    @staticmethod
    def _path(path: str):
        from meshcat.path import Path as MeshcatPath

        return MeshcatPath(tuple(p for p in path.split("/") if p))

    def add(self, path: str, shape, rgba: Sequence[float], transform: np.ndarray) -> None:
        """Add a primitive at `path` with a colour (rgba 0..1) and a 4x4 world transform."""
        material = self.geometry.MeshPhongMaterial(color=_hex(rgba), opacity=float(rgba[3]), transparent=bool(rgba[3] < 1))
        self._send(self._SetObject(shape, material, self._path(path)))
        self.set_transform(path, transform)

    def set_transform(self, path: str, transform: np.ndarray) -> None:
        self._send(self._SetTransform(np.asarray(transform, dtype=float), self._path(path)))

    def set_property(self, path: str, key: str, value) -> None:
        self._send(self._SetProperty(key, value, self._path(path)))

    def frame_camera(self, lo: np.ndarray, hi: np.ndarray, root: str = "/mechanism",
                     direction=(1.0, -1.6, 0.9)) -> None:
        """Centre the drawing under `root` on the origin (meshcat orbits the origin) and place the camera
        along `direction` (world) far enough to see the box [lo, hi]; hide the grid and axes."""
        centre = (lo + hi) / 2
        radius = max(float(np.linalg.norm(hi - lo)) / 2, 1e-3)
        d = np.asarray(direction, dtype=float)
        offset = d / np.linalg.norm(d) * radius * 2.4
        self.set_transform(root, pin.SE3(np.eye(3), -centre).homogeneous)
        # the camera lives in meshcat's y-up "rotated" frame: world (x, y, z) -> (x, z, -y)
        self.set_property("/Cameras/default/rotated/<object>", "position", [offset[0], offset[2], -offset[1]])
        self.set_property("/Grid", "visible", False)
        self.set_property("/Axes", "visible", False)

    def html(self, title: str = "mechkit") -> str:
        """The page: meshcat's viewer script inlined, then every command."""
        import meshcat

        script = (Path(meshcat.__file__).parent / "viewer" / "dist" / "main.min.js").read_text()
        blobs = ",\n".join(f'"{base64.b64encode(c).decode()}"' for c in self._commands)
        return f"""<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>{title}</title>
<style>body {{margin: 0}} #meshcat-pane {{width: 100vw; height: 100vh; overflow: hidden}}</style></head>
<body><div id="meshcat-pane"></div>
<script>{script}</script>
<script>
var viewer = new MeshCat.Viewer(document.getElementById("meshcat-pane"));
const commands = [
{blobs}
];
for (const blob of commands) {{
  viewer.handle_command_bytearray(Uint8Array.from(atob(blob), c => c.charCodeAt(0)));
}}
</script></body></html>
"""


def mechanism_scene(mechanism, q: np.ndarray, prefix: str = "/mechanism", offset: np.ndarray | None = None,
                    scene: StaticScene | None = None) -> tuple[StaticScene, np.ndarray, np.ndarray]:
    """Draw a mechanism at q: links, joints (actuated red), loop cuts (yellow), ground plate.

    Returns (scene, lower corner, upper corner) of the drawn points (world, m).
    """
    scene = scene or StaticScene()
    g = scene.geometry
    model = mechanism.model
    shift = np.zeros(3) if offset is None else np.asarray(offset, dtype=float)
    T_shift = pin.SE3(np.eye(3), shift)
    visual = visual_model(mechanism)
    vdata = visual.createData()
    data = model.createData()
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    pin.updateGeometryPlacements(model, data, visual, vdata)
    points = []
    size = _characteristic_size(mechanism, data)
    for k, obj in enumerate(visual.geometryObjects):
        primitive = _shape(g, obj.geometry)
        if primitive is None:
            continue
        shape, local = primitive
        placement = T_shift * vdata.oMg[k] * pin.SE3(local, np.zeros(3))
        scene.add(f"{prefix}/links/{obj.name}", shape, [float(c) for c in obj.meshColor], placement.homogeneous)
        points.append(placement.translation)
    actuated = set(mechanism.actuated)
    for j in range(1, model.njoints):
        oMi = T_shift * data.oMi[j]
        axis = _joint_axis(model, data, j)
        colour = (0.85, 0.1, 0.1, 1.0) if model.names[j] in actuated else (0.15, 0.15, 0.15, 1.0)
        if axis is not None:
            R = _rotation_y_to(oMi.rotation @ axis)
            scene.add(f"{prefix}/joints/{model.names[j]}", g.Cylinder(size * 0.8, size * 0.2), colour,
                      pin.SE3(R, oMi.translation).homogeneous)
        points.append(oMi.translation)
    for closure in mechanism.closures:
        p = (T_shift * data.oMf[model.getFrameId(closure.frame_b)]).translation
        scene.add(f"{prefix}/cuts/{closure.name}", g.Sphere(size * 0.18), (1.0, 0.8, 0.0, 1.0), pin.SE3(np.eye(3), p).homogeneous)
        points.append(p)
    supports = [(T_shift * data.oMi[j]).translation for j in range(1, model.njoints) if model.parents[j] == 0]
    for i, p in enumerate(supports):
        scene.add(f"{prefix}/ground/{i}", g.Box([size * 0.6, size * 0.6, size * 0.6]), (0.55, 0.55, 0.55, 1.0),
                  pin.SE3(np.eye(3), p).homogeneous)
    pts = np.array(points) if points else np.zeros((1, 3))
    return scene, pts.min(axis=0), pts.max(axis=0)


def visual_model(mechanism) -> pin.GeometryModel:
    """Pinocchio visual geometry (primitives) of the mechanism's URDF."""
    return pin.buildGeomFromUrdfString(mechanism.model, mechanism.urdf, pin.GeometryType.VISUAL)


def _characteristic_size(mechanism, data) -> float:
    pts = np.array([data.oMi[j].translation for j in range(mechanism.model.njoints)])
    span = float(np.max(np.ptp(pts, axis=0))) if len(pts) > 1 else 0.1
    return max(span, 1e-3) * 0.05


def _shape(g, geometry) -> tuple[object, np.ndarray] | None:
    """Meshcat primitive for a coal shape, and the local rotation that aligns it (meshcat cylinders lie along y, coal's along z)."""
    name = type(geometry).__name__
    if name == "Box":
        return g.Box(list(2 * np.asarray(geometry.halfSide))), np.eye(3)
    if name == "Sphere":
        return g.Sphere(float(geometry.radius)), np.eye(3)
    if name == "Cylinder":
        return g.Cylinder(2 * float(geometry.halfLength), float(geometry.radius)), pin.rpy.rpyToMatrix(np.pi / 2, 0, 0)
    return None


def _joint_axis(model: pin.Model, data: pin.Data, j: int) -> np.ndarray | None:
    """Axis of a one-coordinate joint in its own frame (rotation axis, or translation for prismatic)."""
    joint = model.joints[j]
    if joint.nv != 1:
        return None
    col = pin.getJointJacobian(model, data, j, pin.ReferenceFrame.LOCAL)[:, joint.idx_v]
    vec = col[3:] if np.linalg.norm(col[3:]) > 1e-12 else col[:3]
    return vec / np.linalg.norm(vec)


def _rotation_y_to(direction: np.ndarray) -> np.ndarray:
    """A rotation taking +y onto `direction` (meshcat cylinders lie along y)."""
    y = np.array([0.0, 1.0, 0.0])
    d = direction / np.linalg.norm(direction)
    v, c = np.cross(y, d), float(y @ d)
    if np.linalg.norm(v) < 1e-12:
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    K = pin.skew(v)
    return np.eye(3) + K + K @ K / (1 + c)


def snapshot(mechanism, q: np.ndarray | None = None, path: str | os.PathLike | None = None) -> str:
    """Self-contained HTML of the mechanism at q (default: its home assembly); written to `path` if given."""
    q = mechanism.home_q if q is None else q
    scene, lo, hi = mechanism_scene(mechanism, q)
    scene.frame_camera(lo, hi, root="/mechanism")
    html = scene.html(mechanism.spec.name)
    if path is not None:
        write_text(path, html)
    return html


def snapshot_command(mechanism, q: str | None = None, scene: str | None = None, html: str | None = None,
                     png: str | None = None) -> list[Path]:
    """What `mechkit snapshot` does: the HTML of a pose (inputs `q`, comma-separated) or of an animated
    scene, and optionally its PNG screenshot. Returns the files written."""
    if scene is not None:
        raise MechkitError("animated scenes are not implemented yet")
    if png is not None:
        raise MechkitError("PNG screenshots are not implemented yet")
    if html is None:
        raise MechkitError("give -o FILE.html")
    pose = None if q is None else mechanism.assemble([float(x) for x in q.split(",")], guess=mechanism.home_q)
    snapshot(mechanism, pose, html)
    return [Path(html)]
