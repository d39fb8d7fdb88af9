"""What is drawn of a mechanism, with primitives only, and where each primitive sits at a configuration.

Links are the URDF visuals in their URDF colours (a palette per limb when the URDF gives none):
primitives, and meshes (STL, OBJ, DAE; found as `mechkit.viz.meshes` says, a missing one is a
placeholder); a body with no visual drawn (none in its file, a missing mesh, a reader's tree with no
URDF) is a bar from its joint to each child joint and cut frame; joints are short cylinders along
their axis, actuated ones red and thicker (spheres for multi-coordinate joints); loop cuts are
yellow spheres; the ground is grey (anchors at the supports, joined by bars when the URDF draws no
ground body). Sizes scale with the mechanism (its joint extent at home); placements are 4x4 world
transforms (m).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from mechkit.mechanism import Mechanism
from mechkit.scenes import joint_extent
from mechkit.viz.meshcat_page import StaticScene
from mechkit.viz.meshes import MISSING, MeshSearch, mesh_geometry, resolve_meshes

ACTUATED = (0.85, 0.08, 0.08, 1.0)
PASSIVE = (0.15, 0.15, 0.18, 1.0)
CUT = (1.0, 0.78, 0.0, 1.0)
GROUND = (0.3, 0.3, 0.32, 1.0)
LIMB_PALETTE = (
    (0.85, 0.33, 0.1),
    (0.2, 0.45, 0.8),
    (0.3, 0.65, 0.3),
    (0.6, 0.4, 0.7),
    (0.9, 0.6, 0.15),
    (0.25, 0.65, 0.7),
)
GHOST_OPACITY = 0.22


@dataclass(frozen=True)
class Part:
    """One drawn primitive or mesh: meshcat path (relative to the drawing's root), shape, colour, bounds."""

    path: str
    shape: object
    rgba: tuple[float, float, float, float]
    half_extent: np.ndarray  # half sizes of its bounding box, in its own frame (m, or mesh file units)
    centre: np.ndarray = field(default_factory=lambda: np.zeros(3))  # centre of that box in its own frame (same units)

    def corners(self, placement: np.ndarray) -> np.ndarray:
        """The 8 corners of the part's bounding box at a 4x4 world placement (which may scale a mesh).

        Args:
            placement: the part's 4x4 world placement (m; it may scale a mesh).

        Returns:
            (8, 3) corners, world, m.
        """
        signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
        return (signs * self.half_extent + self.centre) @ placement[:3, :3].T + placement[:3, 3]


class Drawing:
    """What is drawn of one mechanism, and where each part sits at any configuration.

    Args:
        mechanism: the mechanism.
        size: marker scale (m); default: the extent of the joint origins at its home configuration.
        meshes: where mesh files are looked for (default: absolute file names only).

    Warns:
        MissingMesh: a mesh file was not found (a placeholder is drawn).
    """

    def __init__(self, mechanism: Mechanism, size: float | None = None, meshes: MeshSearch | None = None):
        self.mechanism = mechanism
        model = mechanism.model
        self.model, self.data = model, model.createData()
        g = StaticScene().geometry
        self.size = joint_extent(model, self.data, mechanism.home_q) if size is None else float(size)
        s = self.size
        self.visual, placeholders = pin.GeometryModel(), set()  # a reader's tree URDF lacks: no visuals
        source = mechanism.urdf or mechanism.source_urdf  # a built tree (a base, a reduction) keeps its links'
        if source is not None:
            urdf, missing = resolve_meshes(source, meshes or MeshSearch(), 0.04 * s)
            try:
                self.visual, placeholders = pin.GeometryModel(), missing
                self.visual = pin.buildGeomFromUrdfString(model, urdf, pin.GeometryType.VISUAL)
            except (RuntimeError, ValueError):  # the built tree lacks a link the URDF draws: bars only
                if mechanism.urdf is not None:
                    raise
                self.visual, placeholders = pin.GeometryModel(), set()
        self.vdata = self.visual.createData()
        self.parts: list[Part] = []
        self._links: list[tuple[int, np.ndarray]] = []  # (geometry index, 4x4 local transform)
        colours = _link_colours(model, self.visual)
        for k, obj in enumerate(self.visual.geometryObjects):
            primitive = _shape(g, obj)
            if primitive is not None:
                shape, local, half, centre = primitive
                colour = MISSING if obj.name in placeholders else colours[k]
                self.parts.append(Part(f"links/{obj.name}", shape, colour, half, centre))
                self._links.append((k, local))
        drawn = {obj.parentJoint for obj in self.visual.geometryObjects if obj.name not in placeholders}
        self._bars = _bars(model, mechanism.closures, drawn)  # (joint, 4x4 in its frame, half length)
        for j, _, half_length in self._bars:
            half = np.array([0.008, half_length / s, 0.008]) * s
            self.parts.append(
                Part(f"links/bar_{model.names[j]}_{len(self.parts)}", g.Box(list(2 * half)), PASSIVE, half)
            )
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
        supports = np.array(
            [model.jointPlacements[j].translation for j in range(1, model.njoints) if model.parents[j] == 0]
        )
        if len(supports) == 0:
            return []
        centre_z = (supports[:, 2].min() + supports[:, 2].max()) / 2
        side = 0.06 * s
        out = []
        for i, p in enumerate(np.unique(np.round(supports, 9), axis=0)):
            below = -1.0 if p[2] <= centre_z + 1e-9 else 1.0  # anchors sit on the outer side of the supports
            centre = p + np.array([0.0, 0.0, below * side / 2])
            out.append(
                (
                    Part(f"ground/anchor{i}", g.Box([side] * 3), GROUND, np.full(3, side / 2)),
                    pin.SE3(np.eye(3), centre).homogeneous,
                )
            )
        drawn = any(obj.parentJoint == 0 for obj in self.visual.geometryObjects)
        if drawn:
            return out
        anchors = np.array([placement[:3, 3] for _, placement in out])
        for i, (a, b) in enumerate(_spanning_tree(anchors)):
            d = anchors[b] - anchors[a]
            thick = 0.025 * s
            half = np.array([thick, np.linalg.norm(d) / 2, thick / 2])
            rotation = _rotation_y_to(d)
            out.append(
                (
                    Part(f"ground/bar{i}", g.Box(list(2 * half)), GROUND, half),
                    pin.SE3(rotation, (anchors[a] + anchors[b]) / 2).homogeneous,
                )
            )
        return out

    def placements(self, q: np.ndarray) -> list[np.ndarray]:
        """4x4 world placement (m) of every part at q, in the order of `parts`.

        Args:
            q: a configuration (nq,).

        Returns:
            The placements (4, 4), one per part.
        """
        model, data = self.model, self.data
        pin.framesForwardKinematics(model, data, q)
        pin.updateGeometryPlacements(model, data, self.visual, self.vdata)
        out = [self.vdata.oMg[k].homogeneous @ local for k, local in self._links]
        out.extend(data.oMi[j].homogeneous @ local for j, local, _ in self._bars)
        for j, axis in self._joints:
            oMi = data.oMi[j]
            rotation = np.eye(3) if axis is None else _rotation_y_to(oMi.rotation @ axis)
            out.append(pin.SE3(rotation, oMi.translation).homogeneous)
        out.extend(pin.SE3(np.eye(3), data.oMf[f].translation).homogeneous for f in self._cuts)
        out.extend(placement for _, placement in self._ground)
        return out

    def corners(self, q: np.ndarray) -> np.ndarray:
        """Corners of every drawn primitive at q (world, m), for framing.

        Args:
            q: a configuration (nq,).

        Returns:
            (8 * parts, 3) corners, world, m.
        """
        return np.vstack([part.corners(T) for part, T in zip(self.parts, self.placements(q))])

    def draw(self, scene: StaticScene, q: np.ndarray, prefix: str = "/mechanism", ghost: bool = False) -> None:
        """Add every part at q under `prefix`; a ghost is the links only, faded.

        Args:
            scene: the scene drawn into.
            q: a configuration (nq,).
            prefix: the meshcat path of the drawing.
            ghost: draw a faded ghost (links only).
        """
        for part, placement in zip(self.parts, self.placements(q)):
            if ghost and not part.path.startswith("links/"):
                continue
            rgba = (*part.rgba[:3], GHOST_OPACITY) if ghost else part.rgba
            scene.add(f"{prefix}/{part.path}", part.shape, rgba, placement)


def _bars(model: pin.Model, closures, drawn: set[int]) -> list[tuple[int, np.ndarray, float]]:
    """For each moving body without a drawn visual, a bar from its joint's origin to each child joint's
    origin and each cut frame on it: (joint, 4x4 placement of the bar's centre in the joint frame, the
    bar's half length (m)), the bar along its placement's y."""
    ends: dict[int, list[np.ndarray]] = {j: [] for j in range(1, model.njoints) if j not in drawn}
    for j in range(1, model.njoints):
        if model.parents[j] in ends:
            ends[model.parents[j]].append(model.jointPlacements[j].translation)
    for closure in closures:
        for frame in (closure.frame_a, closure.frame_b):
            f = model.frames[model.getFrameId(frame)]
            if f.parentJoint in ends:
                ends[f.parentJoint].append(f.placement.translation)
    out = []
    for j, points in ends.items():
        for end in points:
            length = float(np.linalg.norm(end))
            if length > 1e-9:
                out.append((j, pin.SE3(_rotation_y_to(end), end / 2).homogeneous, length / 2))
    return out


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


def _shape(g, obj: pin.GeometryObject) -> tuple[object, np.ndarray, np.ndarray, np.ndarray] | None:
    """Meshcat geometry of a visual, the 4x4 local transform that places it in the visual's frame
    (meshcat cylinders lie along y, coal's along z; a mesh file is scaled by the URDF's scale), and the
    half sizes and centre of its bounding box in meshcat's frame; None for a shape not drawn."""
    geometry = obj.geometry
    name = type(geometry).__name__
    if name == "Box":
        half = np.asarray(geometry.halfSide, dtype=float)
        return g.Box(list(2 * half)), np.eye(4), half, np.zeros(3)
    if name == "Sphere":
        r = float(geometry.radius)
        return g.Sphere(r), np.eye(4), np.full(3, r), np.zeros(3)
    if name == "Cylinder":
        r, h = float(geometry.radius), float(geometry.halfLength)
        local = pin.SE3(pin.rpy.rpyToMatrix(np.pi / 2, 0, 0), np.zeros(3)).homogeneous
        return g.Cylinder(2 * h, r), local, np.array([r, h, r]), np.zeros(3)
    if name.startswith("BVHModel") and obj.meshPath:
        scale = np.asarray(obj.meshScale, dtype=float)  # coal loaded the mesh scaled; meshcat reads the file
        vertices = np.asarray(geometry.vertices(), dtype=float) / scale
        low, high = vertices.min(axis=0), vertices.max(axis=0)
        shape = mesh_geometry(g, obj.meshPath, vertices, geometry)
        return shape, np.diag([*scale, 1.0]), (high - low) / 2, (high + low) / 2
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
        col = pin.getJointJacobian(model, data, j, pin.ReferenceFrame.LOCAL).reshape(6, -1)[:, joint.idx_v]
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
