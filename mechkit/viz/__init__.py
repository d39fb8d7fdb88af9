"""Meshcat pictures of a mechanism: self-contained HTML of a pose, of an animated scene, of a scene's
poses overlaid, or of several configurations side by side (URDF primitives and meshes); PNG
screenshots through headless Chromium; a live viewer; inline views in Jupyter.

Modules, bottom up:
    meshcat_page: `StaticScene`, the offline meshcat HTML page (commands inlined, no server).
    browser: headless-Chromium screenshots of a page, and a picture's coverage.
    camera: framing (camera direction from the spec's `view` or the mechanism's shape, distance).
    drawing: `Part`, `Drawing`: the primitives of a mechanism, their colours and placements.
    meshes: `MeshSearch` (where URDF mesh files are found), `MissingMesh` (a warning; placeholder drawn).
    pages: `snapshot`, `animation`, `overlay`, `side_by_side`, `mechanism_scene`, `snapshot_command`.
    live: `LiveViewer`, `view`: a meshcat server on 127.0.0.1 showing a pose or playing a scene.
    inline: `show` (a notebook view of a pose or a scene), `register` (a Mechanism displays inline).
    gallery: `picture` (a mechanism's gallery picture and caption), `table` (the gallery page).

Scenes (named motions) live in `mechkit.scenes`.
"""

from mechkit.viz.drawing import Drawing, Part
from mechkit.viz.meshcat_page import StaticScene
from mechkit.viz.pages import animation, mechanism_scene, overlay, side_by_side, snapshot, snapshot_command

__all__ = [
    "Drawing",
    "Part",
    "StaticScene",
    "animation",
    "mechanism_scene",
    "overlay",
    "side_by_side",
    "snapshot",
    "snapshot_command",
]
