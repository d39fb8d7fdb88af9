"""Pictures of a mechanism as self-contained HTML pages: a pose, an animated scene, a scene's poses
overlaid, several configurations side by side; and `mechkit snapshot` (HTML and/or PNG).

Scenes come from `mechkit.scenes` (the spec's own, plus the generic input sweep). Animations play the
poses at an even pace (at most MAX_FRAMES of them, evenly picked), ping-pong, 4 to 12 s per pass
whatever the scene's own duration (meshcat's controls change the speed). Nothing here prints or opens
a window; a PNG is an explicit call to `mechkit.viz.browser`.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pinocchio as pin

from mechkit.base.atomic import check_distinct, write_text
from mechkit.base.exceptions import InvalidArgument, InvalidParameters
from mechkit.mechanism import Mechanism
from mechkit.scenes import scene_poses
from mechkit.viz.browser import find_chromium, screenshot
from mechkit.viz.camera import frame_camera, view_direction
from mechkit.viz.drawing import Drawing
from mechkit.viz.meshcat_page import StaticScene
from mechkit.viz.meshes import MeshSearch

MAX_FRAMES = 240  # poses kept in an animation (the page grows with frames x parts)


def compose(
    scene: StaticScene,
    mechanism: Mechanism,
    poses: Sequence[np.ndarray],
    *,
    animate: bool = False,
    ghosts: int = 0,
    meshes: MeshSearch | None = None,
    root: str = "/mechanism",
) -> None:
    """Draw the mechanism into a scene, framed: at poses[-1] (with `ghosts` faded earlier poses), or
    animated along poses (at most MAX_FRAMES of them).

    Args:
        scene: the scene drawn into.
        mechanism: the mechanism.
        poses: configurations (nq,) each.
        animate: animate along the poses instead.
        ghosts: faded earlier poses drawn beside the last.
        meshes: where mesh files are looked for.
        root: the meshcat path of the drawing.
    """
    drawing = Drawing(mechanism, meshes=meshes)
    scene.set_background()
    if animate:
        shown = [poses[int(i)] for i in np.linspace(0, len(poses) - 1, min(len(poses), MAX_FRAMES)).round()]
        drawing.draw(scene, shown[0], f"{root}/pose")
    else:  # ghosts evenly spread from the first pose, then the last pose (periodic scenes: no ghost on it)
        picks = [poses[int(i)] for i in np.linspace(0, len(poses) - 1, ghosts + 1).round()] if ghosts else []
        shown = [q for q in picks[:-1] if np.max(np.abs(q - poses[-1])) > 1e-9] + [poses[-1]]
        for i, q in enumerate(shown[:-1]):
            drawing.draw(scene, q, f"{root}/ghost{i}", ghost=True)
        drawing.draw(scene, shown[-1], f"{root}/pose")
    points = np.vstack([drawing.corners(q) for q in shown])
    frame_camera(scene, points, root, view_direction(mechanism))
    if animate:
        frames = [drawing.placements(q) for q in shown]
        tracks = {}
        for k, part in enumerate(drawing.parts):
            path = [frame[k] for frame in frames]
            if max(float(np.max(np.abs(T - path[0]))) for T in path) > 1e-12:  # fixed parts need no track
                tracks[f"{root}/pose/{part.path}"] = path
        fps = len(shown) / min(max(len(shown) / 30, 4.0), 12.0)
        scene.set_animation(tracks, fps)


def _page(
    mechanism: Mechanism,
    poses: Sequence[np.ndarray],
    *,
    animate: bool = False,
    ghosts: int = 0,
    caption: str = "",
    meshes: MeshSearch | None = None,
) -> str:
    """HTML of the mechanism (see `compose`)."""
    scene = StaticScene()
    compose(scene, mechanism, poses, animate=animate, ghosts=ghosts, meshes=meshes)
    return scene.html(mechanism.spec.name, caption)


def mechanism_scene(
    mechanism: Mechanism, q: np.ndarray, prefix: str = "/mechanism", scene: StaticScene | None = None
) -> tuple[StaticScene, np.ndarray, np.ndarray]:
    """Draw a mechanism at q into a scene (new one by default).

    Args:
        mechanism: the mechanism.
        q: a configuration (nq,).
        prefix: the meshcat path of the drawing.
        scene: the scene drawn into (default: a new one).

    Returns:
        (scene, lower corner, upper corner) of the drawn primitives (world, m).
    """
    scene = scene or StaticScene()
    drawing = Drawing(mechanism)
    drawing.draw(scene, q, prefix)
    corners = drawing.corners(q)
    return scene, corners.min(axis=0), corners.max(axis=0)


def snapshot(
    mechanism: Mechanism,
    q: np.ndarray | None = None,
    path: str | os.PathLike | None = None,
    *,
    meshes: MeshSearch | None = None,
) -> str:
    """Self-contained HTML of the mechanism at q (default: its home assembly).

    Args:
        mechanism: the mechanism.
        q: a configuration (nq,), assembled.
        path: where the page is written, if given.
        meshes: where mesh files are looked for.

    Returns:
        The HTML text.

    Raises:
        OutputError: `path` cannot be written.
    """
    q = mechanism.home_q if q is None else np.asarray(q, dtype=float)
    html = _page(mechanism, [q], caption=f"{mechanism.spec.name}: {mechanism.spec.summary}", meshes=meshes)
    if path is not None:
        write_text(path, html)
    return html


def animation(
    mechanism: Mechanism,
    scene: str,
    path: str | os.PathLike | None = None,
    *,
    poses: Sequence[np.ndarray] | None = None,
    meshes: MeshSearch | None = None,
) -> str:
    """Self-contained HTML animating one of the mechanism's scenes.

    Args:
        mechanism: the mechanism.
        scene: one of its scenes.
        path: where the page is written, if given.
        poses: the scene's poses when already computed (by `mechkit.scenes.scene_poses`).
        meshes: where mesh files are looked for.

    Returns:
        The HTML text.

    Raises:
        InvalidParameters: no such scene.
        OutputError: `path` cannot be written.
    """
    poses = scene_poses(mechanism, scene) if poses is None else poses
    html = _page(
        mechanism,
        poses,
        animate=True,
        caption=f"{mechanism.spec.name}, scene {scene!r}: {len(poses)} poses",
        meshes=meshes,
    )
    if path is not None:
        write_text(path, html)
    return html


def overlay(
    mechanism: Mechanism,
    scene: str,
    ghosts: int = 3,
    path: str | os.PathLike | None = None,
    *,
    poses: Sequence[np.ndarray] | None = None,
    meshes: MeshSearch | None = None,
) -> str:
    """Self-contained HTML of a scene as one picture: its last pose, and `ghosts` earlier poses (evenly
    spread from the first) faded.

    Args:
        mechanism: the mechanism.
        scene: one of its scenes.
        ghosts: how many earlier poses.
        path: where the page is written, if given.
        poses: the scene's poses when already computed.
        meshes: where mesh files are looked for.

    Returns:
        The HTML text.

    Raises:
        InvalidParameters: no such scene.
        OutputError: `path` cannot be written.
    """
    poses = scene_poses(mechanism, scene) if poses is None else poses
    html = _page(mechanism, poses, ghosts=ghosts, caption=f"{mechanism.spec.name}, scene {scene!r}", meshes=meshes)
    if path is not None:
        write_text(path, html)
    return html


def side_by_side(
    mechanism: Mechanism, poses: Sequence[np.ndarray], path: str | os.PathLike | None = None, caption: str = ""
) -> str:
    """Self-contained HTML of several configurations drawn next to each other along world x (e.g. every
    assembly of one set of inputs); written to `path` if given.

    Args:
        mechanism: the mechanism.
        poses: configurations (nq,) each.
        path: where the page is written, if given.
        caption: a line of text on the page.

    Returns:
        The HTML text.

    Raises:
        InvalidParameters: no configuration.
        OutputError: `path` cannot be written.
    """
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
    frame_camera(scene, np.vstack(points), "/mechanism", view_direction(mechanism))
    html = scene.html(mechanism.spec.name, caption or f"{mechanism.spec.name}: {len(poses)} configurations")
    if path is not None:
        write_text(path, html)
    return html


def snapshot_command(
    mechanism: Mechanism,
    q: Sequence[float] | None = None,
    scene: str | None = None,
    html: str | None = None,
    png: str | None = None,
    meshes: MeshSearch | None = None,
) -> list[Path]:
    """What `mechkit snapshot` does: the HTML of a pose or of an animated scene, and optionally a PNG
    screenshot (of the pose; of a scene, its overlay picture).

    Args:
        mechanism: the mechanism.
        q: the inputs of the pose, in actuated order (rad or m).
        scene: a scene to animate instead.
        html: the page's file.
        png: the screenshot's file.
        meshes: where mesh files are looked for.

    Returns:
        The files written.

    Raises:
        InvalidArgument: neither html nor png.
        InvalidParameters: both q and scene, inputs the assembly refuses, an unknown scene.
        MethodUnavailable: no Chromium for the PNG.
        OutputError: a file cannot be written.
    """
    if html is None and png is None:
        raise InvalidArgument("output", None, "give -o FILE.html, --png FILE.png, or both")
    if q is not None and scene is not None:
        raise InvalidParameters("q", q, "give either --q (one pose) or --scene (an animation), not both")
    if png is not None:
        find_chromium()  # fail before any work when there is no browser
        check_distinct([p for p in (html, png) if p is not None])
    written: list[Path] = []
    if scene is not None:
        poses = scene_poses(mechanism, scene)
        if html is not None:
            animation(mechanism, scene, html, poses=poses, meshes=meshes)
            written.append(Path(html))
        page = overlay(mechanism, scene, poses=poses, meshes=meshes) if png is not None else None
    else:
        pose = None if q is None else mechanism.assemble(list(q), guess=mechanism.home_q)
        page = snapshot(mechanism, pose, html, meshes=meshes)
        if html is not None:
            written.append(Path(html))
    if png is not None:
        with tempfile.TemporaryDirectory(prefix="mechkit-snapshot-") as tmp:
            source = Path(html) if html is not None and scene is None else write_text(Path(tmp) / "page.html", page)
            written.append(screenshot(source, png))
    return written
