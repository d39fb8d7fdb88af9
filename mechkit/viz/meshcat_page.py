"""A self-contained meshcat HTML page: an ordered list of meshcat commands replayed by the inlined viewer.

The page holds meshcat's viewer script and every drawing command (msgpack, base64): it opens offline,
no meshcat server is started. Colours are rgba in 0..1, transforms 4x4 homogeneous matrices in the
world frame (m), paths meshcat scene-tree paths ("/mechanism/pose/links/crank").
"""

from __future__ import annotations

import base64
import html as html_escape
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from mechkit.base.exceptions import MethodUnavailable

BACKGROUND = (0.93, 0.95, 0.97)  # uniform page background (rgb 0..1)
_LOOP_PINGPONG = 2202  # THREE.LoopPingPong


def _meshcat():
    try:
        import umsgpack
        from meshcat import animation, commands, geometry
        from meshcat.path import Path as MeshcatPath
    except ImportError:
        raise MethodUnavailable("snapshots", "meshcat is not installed: pip install 'mechkit[viz]'") from None
    return geometry, umsgpack, commands, animation, MeshcatPath


def _hex(rgba: Sequence[float]) -> int:
    """A three.js colour (0xRRGGBB) from rgb(a) in 0..1 (alpha ignored)."""
    r, g, b = (round(255 * float(c)) for c in rgba[:3])
    return (r << 16) + (g << 8) + b


class StaticScene:
    """An ordered list of meshcat commands that becomes one self-contained HTML page.

    Attributes:
        geometry: the `meshcat.geometry` module (primitives: Box, Sphere, Cylinder).
    """

    def __init__(self) -> None:
        self.geometry, self._umsgpack, self._commands_module, self._animation, self._MeshcatPath = _meshcat()
        self._commands: list[bytes] = []

    def _send(self, lowered: dict) -> None:
        self._commands.append(self._umsgpack.packb(lowered))

    def _path(self, path: str):
        return self._MeshcatPath(tuple(p for p in path.split("/") if p))

    def add(self, path: str, shape: Any, rgba: Sequence[float], transform: np.ndarray) -> None:
        """Add a meshcat primitive at `path` with a colour (rgba 0..1) and a 4x4 world transform (m).

        Args:
            path: the meshcat path.
            shape: a meshcat geometry.
            rgba: the colour, each 0..1.
            transform: its 4x4 world transform (m).
        """
        material = self.geometry.MeshPhongMaterial(
            color=_hex(rgba), opacity=float(rgba[3]), transparent=bool(rgba[3] < 1)
        )
        self._send(self._commands_module.SetObject(shape, material, self._path(path)).lower())
        self.set_transform(path, transform)

    def set_transform(self, path: str, transform: np.ndarray) -> None:
        """Place the object at `path` by a 4x4 transform (m) relative to its parent path.

        Args:
            path: the meshcat path.
            transform: 4x4 transform (m) relative to its parent path.
        """
        self._send(self._commands_module.SetTransform(np.asarray(transform, dtype=float), self._path(path)).lower())

    def set_property(self, path: str, key: str, value: Any) -> None:
        """Set a three.js property of the object at `path` (e.g. a camera's "fov").

        Args:
            path: the meshcat path.
            key: the property.
            value: its value.
        """
        self._send(self._commands_module.SetProperty(key, value, self._path(path)).lower())

    def set_background(self, rgb: Sequence[float] = BACKGROUND) -> None:
        """A uniform background colour (rgb 0..1); also hides meshcat's grid and axes.

        Args:
            rgb: the colour, each 0..1.
        """
        for key in ("top_color", "bottom_color"):
            self.set_property("/Background", key, [float(c) for c in rgb])
        self.set_property("/Grid", "visible", False)
        self.set_property("/Axes", "visible", False)

    def set_animation(self, tracks: dict[str, Sequence[np.ndarray]], fps: float) -> None:
        """Animate objects: `tracks` maps a meshcat path to its 4x4 world transforms, one per frame.

        Lowered from `meshcat.animation.Animation` into one set_animation command that plays at
        `fps` frames per second, ping-pong, forever.

        Args:
            tracks: meshcat path -> its 4x4 world transforms, one per frame.
            fps: frames per second.
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
        address, the page hides the controls and the caption (for screenshots).

        Args:
            title: the page's title.
            caption: a line of text at its bottom left.

        Returns:
            The HTML text, self-contained.
        """
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
