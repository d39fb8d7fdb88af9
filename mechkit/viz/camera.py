"""Framing: where the camera looks from, and how far back it stands to see the whole drawing.

The camera looks along the spec's `view` (world direction from the mechanism to the camera), else
nearly face-on to a planar linkage (its joint origins at home span a thin slab), else obliquely. It
orbits the origin, so the drawing is translated to centre its bounding box there, and stands just far
enough back that every drawn point is in view with a MARGIN around it (z is up in the world frame).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from mechkit.mechanism import Mechanism
from mechkit.viz.meshcat_page import StaticScene

FOV_DEG = 30.0  # vertical field of view of the camera
ASPECT = 4 / 3  # narrowest width/height the framing allows for
MARGIN = 0.08  # fraction of the view kept free around the mechanism
OBLIQUE = (1.0, -1.6, 0.9)  # default camera direction (world, towards the camera)


def view_direction(mechanism: Mechanism) -> tuple[float, float, float]:
    """The camera direction (world, from the mechanism towards the camera): the spec's view, else nearly
    face-on to a planar linkage (its joint origins at home span a thin slab), else oblique.

    Args:
        mechanism: the mechanism.

    Returns:
        The unit direction (3,), world.
    """
    if mechanism.spec.view is not None:
        return mechanism.spec.view
    model = mechanism.model
    data = model.createData()
    pin.forwardKinematics(model, data, mechanism.home_q)
    extent = np.ptp([data.oMi[j].translation for j in range(1, model.njoints)], axis=0)
    thin = int(np.argmin(extent))
    if extent[thin] < 0.3 * extent.max():
        return ((1.0, 0.2, 0.12), (0.2, -1.0, 0.12), (0.2, -0.3, 1.0))[thin]  # nearly face-on
    return OBLIQUE


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


def frame_camera(
    scene: StaticScene, points: np.ndarray, root: str = "/mechanism", direction: Sequence[float] = OBLIQUE
) -> None:
    """Centre the drawing under `root` on the origin and place the scene's camera so every point is in view.

    Args:
        scene: the page whose camera is placed.
        points: (N, 3) world points (m) to keep in view, e.g. the corners of every drawn primitive.
        root: meshcat path of the drawing (translated so the points' bounding box is centred on the
            origin, which meshcat's camera orbits).
        direction: world direction from the mechanism to the camera (z is up).
    """
    pts = np.atleast_2d(np.asarray(points, dtype=float))
    centre = (pts.min(axis=0) + pts.max(axis=0)) / 2
    distance, back = camera_distance(pts - centre, direction)
    scene.set_transform(root, pin.SE3(np.eye(3), -centre).homogeneous)
    position = back * distance
    camera = "/Cameras/default/rotated/<object>"
    # the camera lives in meshcat's y-up "rotated" frame: world (x, y, z) -> (x, z, -y)
    scene.set_property(camera, "position", [position[0], position[2], -position[1]])
    scene.set_property(camera, "fov", FOV_DEG)
    scene.set_property(camera, "near", distance / 100)
    scene.set_property(camera, "far", distance * 20)
