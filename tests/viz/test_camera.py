"""`mechkit.viz.camera`: the camera fit keeps every point in view, and no farther than needed."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechkit.viz import camera


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
