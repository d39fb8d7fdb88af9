"""A natural mode animated in an offline meshcat page: every body moved rigidly by its modal twist
(about its centre of mass), scaled for the eye, one period."""

from __future__ import annotations

import os

import numpy as np
import pinocchio as pin

from mechkit.base.atomic import write_text
from mechkit.elastic.modes import Modes
from mechkit.mechanism import Mechanism
from mechkit.viz.camera import frame_camera, view_direction
from mechkit.viz.drawing import Drawing
from mechkit.viz.meshcat_page import StaticScene

FRAMES = 48  # frames of the period
AMPLITUDE = 0.05  # largest modal translation drawn, as a fraction of the mechanism's size (ours: visible, small)


def _part_bodies(drawing: Drawing, mech: Mechanism) -> list[int]:
    """The body (Pinocchio joint id; 0 = ground) each drawn part moves with, in the order of `parts`."""
    model = mech.model
    out = [int(drawing.visual.geometryObjects[k].parentJoint) for k, _ in drawing._links]
    out += [j for j, _ in drawing._joints]
    out += [int(model.frames[f].parentJoint) for f in drawing._cuts]
    return out + [0] * (len(drawing.parts) - len(out))


def write_mode_page(mech: Mechanism, q: np.ndarray, modes: Modes, mode: int, path: str | os.PathLike) -> str:
    """Write (and return) the HTML page animating one natural mode about a pose.

    Args:
        mech: the mechanism the modes are of.
        q: (nq,) the pose the modes were computed at.
        modes: the modes (`ElasticModel.modes`).
        mode: the mode's index (0-based).
        path: the HTML file to write.

    Returns:
        The page's HTML text.

    Raises:
        InvalidParameters: no such mode.
    """
    from mechkit.base.exceptions import InvalidParameters

    if not 0 <= mode < len(modes.frequencies):
        raise InvalidParameters("mode", mode + 1, f"between 1 and {len(modes.frequencies)}")
    scene = StaticScene()
    drawing = Drawing(mech)
    scene.set_background()
    drawing.draw(scene, q, "/mechanism/pose")
    frame_camera(scene, drawing.corners(q), "/mechanism", view_direction(mech))
    shape = modes.shapes[mode]
    twist = {int(b): (shape[k], modes.centres[k]) for k, b in enumerate(modes.bodies)}
    scale = AMPLITUDE * drawing.size / max(np.abs(shape[:, :3]).max(), 1e-300)
    base = drawing.placements(q)
    tracks = {}
    for part, body, T in zip(drawing.parts, _part_bodies(drawing, mech), base):
        if body not in twist:
            continue
        d, c = twist[body]
        frames = []
        for k in range(FRAMES + 1):
            s = scale * np.sin(2 * np.pi * k / FRAMES)
            R = pin.exp3(s * d[3:])
            move = np.eye(4)
            move[:3, :3], move[:3, 3] = R, c + s * d[:3] - R @ c
            frames.append(move @ T)
        tracks[f"/mechanism/pose/{part.path}"] = frames
    scene.set_animation(tracks, FRAMES / 2.0)
    caption = f"{mech.spec.name}: mode {mode + 1}, {modes.frequencies[mode]:.4g} Hz (motion exaggerated)"
    html = scene.html(mech.spec.name, caption)
    write_text(path, html)
    return html
