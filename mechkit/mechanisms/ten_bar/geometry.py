"""Ten-bar geometry, numpy only: hinge layout, mass properties and the closed-form pose.

Plane x-z of the world (z up), the satellite side wall is the plane x = 0 with the fixed hinges
R1 = (0, 0) and R5 = (0, -wall_gap); the panels deploy towards +x. A planar vector is (x, z); an
absolute angle phi is measured from +x towards +z (the joints turn about -y, so a joint angle is the
child's absolute angle minus the parent's).

Every moving link has a body frame with its origin at its first hinge and its x axis along the
link's line (the patent's l_i,j points from R_i to R_j):

    l123  origin R1, x along panel 1's axis R2 -> R3 (R2, R3, R10 are offsets in this frame)
    l27   R2 -> R7          l34  R3 -> R4 (panel 2's axis)     l48  R4 -> R8     l87  R8 -> R7
    l56   R5 -> R6          l67  R6 -> R7                      l79  R7 -> R9     l910 R9 -> R10

The 12 revolute pairs are the 9 tree joints R1 R2 R3 R4 R5 R6 R7b R8 R9 and the 3 cuts R7a (l27-l67,
five-bar), R7c (l27-l87, six-bar), R10 (l123-l910, four-bar); R7a, R7b, R7c are the three pairs of
the compound hinge R7 (hub l27). The closed-form pose solves the loops in the patent's order: the
five-bar (R7 from R2 and R6), the four-bar (R9 from R7 and R10), the six-bar (R8 from R4 and R7),
each a circle intersection on a fixed branch.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import ClosureNotConverged
from mechkit.mechanisms.ten_bar.params import STOWED, TenBarParams

BODIES = ("l123", "l27", "l34", "l48", "l87", "l56", "l67", "l79", "l910")
"""The 9 moving links, in the order of the Lagrange coordinates."""

TREE_JOINTS = ("R1", "R2", "R3", "R4", "R8", "R5", "R6", "R7b", "R9")
CUT_JOINTS = ("R7a", "R7c", "R10")
PAIRS = TREE_JOINTS + CUT_JOINTS
"""The 12 revolute pairs: tree joints of the URDF, then the loop cuts."""

PAIR_LINKS = {
    "R1": ("wall", "l123", "R1"),
    "R2": ("l123", "l27", "R2"),
    "R3": ("l123", "l34", "R3"),
    "R4": ("l34", "l48", "R4"),
    "R8": ("l48", "l87", "R8"),
    "R5": ("wall", "l56", "R5"),
    "R6": ("l56", "l67", "R6"),
    "R7b": ("l27", "l79", "R7"),
    "R9": ("l79", "l910", "R9"),
    "R7a": ("l27", "l67", "R7"),
    "R7c": ("l27", "l87", "R7"),
    "R10": ("l123", "l910", "R10"),
}
"""Each pair: (parent link or "wall", child link, hinge point)."""

BRANCH = {"R7": 1.0, "R9": -1.0, "R8": 1.0}
"""Assembly branch of each circle intersection (side of the line from the first to the second
centre, +1 = to the left); the branch that keeps every hinge outside the wall (x > 0)."""


@dataclass(frozen=True)
class Hinge:
    """One revolute pair: `parent` (None = the wall) holds `parent_point`, `child` holds `child_point`.

    Points are in the body frames (m); for the wall, in the world frame.
    """

    name: str
    parent: str | None
    parent_point: np.ndarray
    child: str
    child_point: np.ndarray


@dataclass(frozen=True)
class Piece:
    """A uniform bar or plate of a link, between two points of the body frame (m).

    `mass` in kg, `depth` (m) the in-plane size across the bar (adds m depth^2 / 12 to the inertia).
    """

    start: np.ndarray
    end: np.ndarray
    mass: float
    depth: float


def rot(phi: float) -> np.ndarray:
    """2x2 rotation of the x-z plane by phi (rad, +x towards +z).

    Args:
        phi: the angle, rad.

    Returns:
        (2, 2) matrix.
    """
    c, s = np.cos(phi), np.sin(phi)
    return np.array([[c, -s], [s, c]])


def unit(phi: float) -> np.ndarray:
    """Unit vector (2,) of the plane at angle phi (rad) from the x axis.

    Args:
        phi: the angle, rad.

    Returns:
        (2,) unit vector.
    """
    return np.array([np.cos(phi), np.sin(phi)])


def hinge_points(p: TenBarParams) -> dict[str, dict[str, np.ndarray]]:
    """Body-frame coordinates (m) of every hinge on every link (and the wall's, in world).

    Args:
        p: the ten-bar's parameters.

    Returns:
        Link -> hinge -> (2,) point (x, z), m.
    """
    r2 = np.array([p.r2_along, p.r2_normal])
    return {
        "wall": {"R1": np.zeros(2), "R5": np.array([0.0, -p.wall_gap])},
        "l123": {
            "R1": np.zeros(2),
            "R2": r2,
            "R3": r2 + [p.panel1, 0.0],
            "R10": r2 + [p.r10_along, p.r10_normal],
        },
        "l27": {"R2": np.zeros(2), "R7": np.array([p.l27, 0.0])},
        "l34": {"R3": np.zeros(2), "R4": np.array([p.l34, 0.0])},
        "l48": {"R4": np.zeros(2), "R8": np.array([p.l48, 0.0])},
        "l87": {"R8": np.zeros(2), "R7": np.array([p.l87, 0.0])},
        "l56": {"R5": np.zeros(2), "R6": np.array([p.l56, 0.0])},
        "l67": {"R6": np.zeros(2), "R7": np.array([p.l67, 0.0])},
        "l79": {"R7": np.zeros(2), "R9": np.array([p.l79, 0.0])},
        "l910": {"R9": np.zeros(2), "R10": np.array([p.l910, 0.0])},
    }


def hinges(p: TenBarParams) -> tuple[Hinge, ...]:
    """The 12 revolute pairs in `PAIRS` order (parent side first; R7a/R7c/R10 are the cuts).

    Args:
        p: the ten-bar's parameters.

    Returns:
        The pairs: name, parent and child links, points in each.
    """
    h = hinge_points(p)
    out = []
    for name in PAIRS:
        parent, child, point = PAIR_LINKS[name]
        out.append(Hinge(name, None if parent == "wall" else parent, h[parent][point], child, h[child][point]))
    return tuple(out)


def pieces(p: TenBarParams) -> dict[str, tuple[Piece, ...]]:
    """The bars and plates of every link (body frames); the xacro template builds the same ones.

    Args:
        p: the ten-bar's parameters.

    Returns:
        Link -> its pieces (start, end, mass, width).
    """
    h = hinge_points(p)
    rod = p.rod_width * p.rod_thickness * p.rod_density  # kg/m

    def bar(body: str, a: str, b: str) -> Piece:
        start, end = h[body][a], h[body][b]
        return Piece(start, end, rod * float(np.linalg.norm(end - start)), p.rod_width)

    plate1 = p.panel_areal_density * p.panel_width * p.panel1
    plate2 = p.panel_areal_density * p.panel_width * p.panel2
    return {
        "l123": (
            bar("l123", "R1", "R2"),
            bar("l123", "R2", "R10"),
            Piece(h["l123"]["R2"], h["l123"]["R3"], plate1, p.panel_thickness),
        ),
        "l34": (Piece(np.zeros(2), np.array([p.panel2, 0.0]), plate2, p.panel_thickness),),
        "l27": (bar("l27", "R2", "R7"),),
        "l48": (bar("l48", "R4", "R8"),),
        "l87": (bar("l87", "R8", "R7"),),
        "l56": (bar("l56", "R5", "R6"),),
        "l67": (bar("l67", "R6", "R7"),),
        "l79": (bar("l79", "R7", "R9"),),
        "l910": (bar("l910", "R9", "R10"),),
    }


def mass_properties(p: TenBarParams) -> dict[str, tuple[float, np.ndarray, float]]:
    """Per link: mass (kg), COM (body frame, m), inertia about the COM normal to the plane (kg m^2).

    Args:
        p: the ten-bar's parameters.

    Returns:
        Link -> (mass, COM (2,), inertia).
    """
    out = {}
    for body, parts in pieces(p).items():
        m = sum(x.mass for x in parts)
        com = sum(x.mass * (x.start + x.end) / 2 for x in parts) / m
        inertia = 0.0
        for x in parts:
            length = float(np.linalg.norm(x.end - x.start))
            centre = (x.start + x.end) / 2
            inertia += x.mass * (length**2 + x.depth**2) / 12 + x.mass * float(np.sum((centre - com) ** 2))
        out[body] = (m, com, inertia)
    return out


def relative_angles(angles: dict[str, float]) -> dict[str, float]:
    """Tree-joint values (rad) from absolute link angles: child's minus parent's (the wall's is 0).

    Args:
        angles: link -> absolute angle, rad.

    Returns:
        Tree joint -> value, rad.
    """
    return {j: angles[PAIR_LINKS[j][1]] - angles.get(PAIR_LINKS[j][0], 0.0) for j in TREE_JOINTS}


def circle_intersection(
    c1: np.ndarray, r1: float, c2: np.ndarray, r2: float, branch: float, what: str
) -> tuple[np.ndarray, float]:
    """The point at distance r1 from c1 and r2 from c2, left of c1 -> c2 for branch +1.

    Args:
        c1: first centre (2,), m.
        r1: first radius, m.
        c2: second centre (2,), m.
        r2: second radius, m.
        branch: +1 or -1.
        what: the loop, for the error.

    Returns:
        (point (2,), sin of the angle at the point between the two radii: the unit's distance from its singular
            (stretched or folded) pose).

    Raises:
        ClosureNotConverged: the two circles do not meet (the loop cannot close).
    """
    d = c2 - c1
    dist = float(np.hypot(*d))
    along = (r1**2 - r2**2 + dist**2) / (2 * dist)
    h2 = r1**2 - along**2
    if h2 < 0:
        raise ClosureNotConverged(
            float(-h2), 0.0, 0, f"{what}: circles of radii {r1}, {r2} at distance {dist:.4f} m do not meet"
        )
    u = d / dist
    point = c1 + along * u + branch * np.sqrt(h2) * np.array([-u[1], u[0]])
    a, b = c1 - point, c2 - point
    return point, float(abs(a[0] * b[1] - a[1] * b[0]) / (r1 * r2))


@dataclass(frozen=True)
class Pose:
    """A closed-form assembly: absolute link angles (rad), hinge points (world, m), and per loop the
    sine of the angle at its closing hinge (0 at a singular pose)."""

    angles: dict[str, float]
    points: dict[str, np.ndarray]
    margins: dict[str, float]

    def joint_angles(self) -> dict[str, float]:
        """URDF tree-joint values: child's absolute angle minus parent's (rad), in (-pi, pi] except R3."""
        rel = relative_angles(self.angles)
        return {k: v if k == "R3" else float(np.angle(np.exp(1j * v))) for k, v in rel.items()}


def pose(p: TenBarParams, phi1: float, psi3: float, phi5: float) -> Pose:
    """Closed-form assembly from the two motor angles and the passive one.

    Args:
        p: ten-bar parameters.
        phi1: absolute angle of panel 1's axis (R1 joint), rad.
        psi3: angle of panel 2 relative to panel 1 (R3 joint), rad.
        phi5: absolute angle of the wall rocker l56 (R5 joint, the passive DOF), rad.

    Returns:
        The link angles, the hinge points and each unit's margin (sine at its closing hinge).

    Raises:
        ClosureNotConverged: a loop cannot close at these inputs.
    """
    h = hinge_points(p)
    r1 = rot(phi1)
    P = {"R1": np.zeros(2), "R5": h["wall"]["R5"].copy()}
    for name in ("R2", "R3", "R10"):
        P[name] = r1 @ h["l123"][name]
    P["R6"] = P["R5"] + p.l56 * unit(phi5)
    P["R7"], m5 = circle_intersection(P["R2"], p.l27, P["R6"], p.l67, BRANCH["R7"], "five-bar (R7)")
    P["R9"], m4 = circle_intersection(P["R7"], p.l79, P["R10"], p.l910, BRANCH["R9"], "four-bar (R9)")
    P["R4"] = P["R3"] + p.l34 * unit(phi1 + psi3)
    P["R8"], m6 = circle_intersection(P["R4"], p.l48, P["R7"], p.l87, BRANCH["R8"], "six-bar (R8)")

    def ang(a: str, b: str) -> float:
        d = P[b] - P[a]
        return float(np.arctan2(d[1], d[0]))

    angles = {
        "l123": phi1,
        "l34": phi1 + psi3,
        "l56": phi5,
        "l27": ang("R2", "R7"),
        "l67": ang("R6", "R7"),
        "l79": ang("R7", "R9"),
        "l910": ang("R9", "R10"),
        "l48": ang("R4", "R8"),
        "l87": ang("R8", "R7"),
    }
    return Pose(angles, P, {"five_bar": m5, "four_bar": m4, "six_bar": m6})


def stowed_pose(p: TenBarParams) -> Pose:
    """Closed-form stowed assembly.

    Args:
        p: the ten-bar's parameters.

    Returns:
        The pose.
    """
    return pose(p, STOWED["R1"], STOWED["R3"], p.stowed_rocker)
