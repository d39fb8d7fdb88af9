"""Closed-form planar references for the calibration four-bar and five-bar (numpy only).

Plane of motion: world x-z, z up. Revolute axes point along -y, so a positive angle turns +x
towards +z and a planar angle phi is the direction (cos phi, 0, sin phi). Planar vectors here are
(x, z) pairs with the ordinary counter-clockwise orientation: an angular rate w (rad/s) is the
world vector w * (0, -1, 0) and a counter-clockwise planar moment M (N m) is M * (0, -1, 0).

Links are rectangular bars along their local x, from their joint origin to their length L (width
along local z, thickness along y). Kinematics are exact: circle intersection for positions and
exact linear solves of the differentiated loop equation for rates and accelerations. Dynamics are
per-link planar Newton-Euler, solved for every pin force and the actuator torques.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from mechkit.exceptions import InvalidParameters, SingularConfiguration
from mechkit.validation.soc import RANK_TOL

__all__ = [
    "AXIS",
    "Bar",
    "LinkState",
    "PlanarJoint",
    "LinkageState",
    "PlanarDynamics",
    "FourBarGeometry",
    "FiveBarGeometry",
    "four_bar",
    "five_bar",
    "newton_euler",
    "to_world",
]

AXIS = np.array([0.0, -1.0, 0.0])
"""World direction of every revolute axis; rates and planar moments are components along it."""


def to_world(v: np.ndarray) -> np.ndarray:
    """Planar (x, z) vector -> world (3,) vector (x, 0, z)."""
    return np.array([v[0], 0.0, v[1]])


def _unit(angle: float) -> np.ndarray:
    return np.array([np.cos(angle), np.sin(angle)])


def _perp(v: np.ndarray) -> np.ndarray:
    """Planar vector turned +90 degrees (counter-clockwise, +x towards +z)."""
    return np.array([-v[1], v[0]])


def _wrap(angle: float) -> float:
    """Angle in (-pi, pi]."""
    return float(np.pi - np.mod(np.pi - angle, 2.0 * np.pi))


@dataclass(frozen=True)
class Bar:
    """Rectangular aluminium bar along its local x (SI units).

    Attributes:
        length: m, joint origin to tip; the COM is at length / 2.
        width: m, in the plane (local z).
        thickness: m, along y.
        density: kg/m^3.
    """

    length: float
    width: float = 0.02
    thickness: float = 0.01
    density: float = 2700.0

    @property
    def mass(self) -> float:
        """kg."""
        return self.density * self.length * self.width * self.thickness

    @property
    def inertia_planar(self) -> float:
        """kg m^2, about the axis through the COM normal to the plane (y)."""
        return self.mass * (self.length**2 + self.width**2) / 12.0

    def inertia_world(self, angle: float) -> np.ndarray:
        """(3, 3) box inertia about the COM in world axes, the bar at planar ``angle`` (rad)."""
        m, length, w, t = self.mass, self.length, self.width, self.thickness
        local = np.diag([m * (t**2 + w**2), m * (length**2 + w**2), m * (length**2 + t**2)]) / 12.0
        c, s = np.cos(angle), np.sin(angle)
        rot = np.array([[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]])  # columns: local x, y, z
        return rot @ local @ rot.T


@dataclass(frozen=True)
class LinkState:
    """Motion of one bar at one instant (planar (x, z) vectors, m, rad, s).

    Attributes:
        name: link name.
        bar: its geometry and inertia.
        origin: position of its joint origin.
        angle: planar angle of the bar's axis.
        omega: angular rate (about -y).
        alpha: angular acceleration (about -y).
        origin_velocity: velocity of the origin.
        origin_acceleration: acceleration of the origin.
    """

    name: str
    bar: Bar
    origin: np.ndarray
    angle: float
    omega: float
    alpha: float
    origin_velocity: np.ndarray
    origin_acceleration: np.ndarray

    def point(self, s: float) -> np.ndarray:
        """Position of the point at distance ``s`` (m) along the bar."""
        return self.origin + s * _unit(self.angle)

    def point_velocity(self, s: float) -> np.ndarray:
        """Velocity of the point at distance ``s`` along the bar."""
        return self.origin_velocity + s * self.omega * _perp(_unit(self.angle))

    def point_acceleration(self, s: float) -> np.ndarray:
        """Acceleration of the point at distance ``s`` along the bar."""
        e = _unit(self.angle)
        return self.origin_acceleration + s * (self.alpha * _perp(e) - self.omega**2 * e)

    @property
    def tip(self) -> np.ndarray:
        return self.point(self.bar.length)

    @property
    def com(self) -> np.ndarray:
        return self.point(0.5 * self.bar.length)

    @property
    def com_velocity(self) -> np.ndarray:
        return self.point_velocity(0.5 * self.bar.length)

    @property
    def com_acceleration(self) -> np.ndarray:
        return self.point_acceleration(0.5 * self.bar.length)


@dataclass(frozen=True)
class PlanarJoint:
    """A pin of a planar linkage.

    Attributes:
        name: joint name (URDF joint or loop-cut name).
        parent: link on the parent side (frame_a's for a cut), None for the ground.
        child: link on the child side.
        point: planar position (x, z) of the pin, m.
        actuated: whether a motor torque acts about the pin (parent on child, about -y).
    """

    name: str
    parent: str | None
    child: str
    point: np.ndarray
    actuated: bool = False


@dataclass(frozen=True)
class LinkageState:
    """Complete motion of a planar linkage at one instant.

    Attributes:
        links: link name -> its motion.
        joints: every pin, loop cuts included.
        coordinates: joint names of the URDF coordinates q, in order.
        q: joint coordinates (rad): absolute angle for a grounded joint, relative angle (child
            minus parent, wrapped to (-pi, pi]) otherwise.
        qd: their rates (rad/s).
        qdd: their accelerations (rad/s^2).
    """

    links: dict[str, LinkState]
    joints: tuple[PlanarJoint, ...]
    coordinates: tuple[str, ...]
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray

    def joint(self, name: str) -> PlanarJoint:
        """The pin called ``name``."""
        for j in self.joints:
            if j.name == name:
                return j
        raise InvalidParameters("joint", name, f"not a joint of this linkage {[j.name for j in self.joints]}")

    def joint_position(self, name: str) -> np.ndarray:
        """World (3,) position of the pin called ``name``, m."""
        return to_world(self.joint(name).point)


@dataclass(frozen=True)
class PlanarDynamics:
    """Newton-Euler inverse dynamics of a planar linkage.

    Attributes:
        efforts: actuated joint -> motor torque about -y, N m (parent on child).
        reactions: joint -> world wrench (6,) [fx, fy, fz, mx, my, mz] (N, N m) that the parent
            side exerts on the child side at the pin; my = -effort for a driven pin, else 0.
        condition: condition number of the Newton-Euler system.
    """

    efforts: dict[str, float]
    reactions: dict[str, np.ndarray]
    condition: float


@dataclass(frozen=True, kw_only=True)
class _BarsGeometry:
    """Cross-section (m) and material (kg/m^3) shared by all bars; every field must be positive, finite."""

    # ours (not in the sources): an aluminium bar section, the same as the project's URDFs
    width: float = 0.02
    thickness: float = 0.01
    density: float = 2700.0

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if not (np.isfinite(value) and value > 0.0):
                raise InvalidParameters(f.name, value, "must be positive and finite")

    def bar(self, length: float) -> Bar:
        return Bar(length, self.width, self.thickness, self.density)


@dataclass(frozen=True, kw_only=True)
class FourBarGeometry(_BarsGeometry):
    """Four-bar lengths (m) and bar section; pivots A = (0, 0) and D = (ground, 0)."""

    ground: float = 0.30
    crank: float = 0.10
    coupler: float = 0.28
    rocker: float = 0.22


@dataclass(frozen=True, kw_only=True)
class FiveBarGeometry(_BarsGeometry):
    """Five-bar lengths (m) and bar section; pivots A1 = (0, 0) and A2 = (ground, 0)."""

    ground: float = 0.25
    prox1: float = 0.12
    dist1: float = 0.22
    prox2: float = 0.12
    dist2: float = 0.22


def _finite(name: str, value: float) -> float:
    if not np.isfinite(value):
        raise InvalidParameters(name, value, "must be finite")
    return float(value)


_Motion = tuple[np.ndarray, np.ndarray, np.ndarray]  # planar position, velocity, acceleration


def _dyad(
    p: _Motion, q: _Motion, lengths: tuple[float, float], elbow_up: bool, inputs: tuple[str, object]
) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    """Close the dyad of two bars hinged at C: bar u of length lu from P, bar v of length lv from Q.

    Returns (angle, rate, acceleration) of bar u and of bar v. ``elbow_up`` picks C on the left of
    P -> Q (the larger z whenever Q lies right of P). Raises InvalidParameters naming ``inputs``
    when the circles do not meet, SingularConfiguration when the two bars are collinear.
    """
    lu, lv = lengths
    pp, pq = p[0], q[0]
    d = pq - pp
    dist = float(np.hypot(*d))
    along = (lu**2 - lv**2 + dist**2) / (2.0 * dist) if dist > 0.0 else np.inf
    if not lu**2 - along**2 >= 0.0:
        why = f"bars of {lu} m and {lv} m hinged {dist:.6g} m apart do not meet (linkage cannot assemble)"
        raise InvalidParameters(inputs[0], inputs[1], why)
    d_hat = d / dist
    c = pp + along * d_hat + (1.0 if elbow_up else -1.0) * np.sqrt(lu**2 - along**2) * _perp(d_hat)
    eu, ev = (c - pp) / lu, (c - pq) / lv
    matrix = np.column_stack([lu * _perp(eu), -lv * _perp(ev)])
    sv = np.linalg.svd(matrix, compute_uv=False)
    if sv[1] <= RANK_TOL * sv[0]:
        cond = np.inf if sv[1] == 0.0 else float(sv[0] / sv[1])
        raise SingularConfiguration(cond, f"the two bars meeting at the loop cut are collinear ({inputs[0]})")
    rates = np.linalg.solve(matrix, q[1] - p[1])
    accel_rhs = q[2] - p[2] + lu * rates[0] ** 2 * eu
    accels = np.linalg.solve(matrix, accel_rhs - lv * rates[1] ** 2 * ev)
    angles = (np.arctan2(eu[1], eu[0]), np.arctan2(ev[1], ev[0]))
    return (angles[0], rates[0], accels[0]), (angles[1], rates[1], accels[1])


def _grounded(name: str, bar: Bar, pivot: np.ndarray, motion: tuple[float, float, float]) -> LinkState:
    return LinkState(name, bar, pivot, *motion, np.zeros(2), np.zeros(2))


def _hinged(name: str, bar: Bar, parent: LinkState, motion: tuple[float, float, float]) -> LinkState:
    tip, velocity, acceleration = _tip_motion(parent)
    return LinkState(name, bar, tip, *motion, velocity, acceleration)


def _tip_motion(link: LinkState) -> _Motion:
    s = link.bar.length
    return link.point(s), link.point_velocity(s), link.point_acceleration(s)


def _relative(child: tuple[float, float, float], parent: tuple[float, float, float]) -> np.ndarray:
    """(angle, rate, acceleration) of a joint between two links from their absolute ones."""
    return np.array([_wrap(child[0] - parent[0]), child[1] - parent[1], child[2] - parent[2]])


def four_bar(
    theta: float,
    rate: float = 0.0,
    acceleration: float = 0.0,
    geometry: FourBarGeometry = FourBarGeometry(),
    elbow_up: bool = True,
) -> LinkageState:
    """Exact motion of the four-bar from the crank's angle and its two derivatives.

    Joints: "crank" at A = (0, 0) (ground -> crank, actuated), "coupler" at the crank tip B
    (crank -> coupler, relative angle), "rocker" at D = (ground, 0) (ground -> rocker), loop cut
    "C" (coupler tip, parent side, meets rocker tip). q = [theta, phi2, theta3].

    Args:
        theta: crank angle, rad. rate: rad/s. acceleration: rad/s^2.
        geometry: lengths and bar section.
        elbow_up: C on the open (larger z) branch; False for the crossed one.

    Raises:
        InvalidParameters: non-finite input or a crank angle at which the linkage cannot assemble.
        SingularConfiguration: coupler and rocker collinear.
    """
    inputs = (("theta", theta), ("rate", rate), ("acceleration", acceleration))
    crank_motion = tuple(_finite(n, v) for n, v in inputs)
    g = geometry
    crank = _grounded("crank", g.bar(g.crank), np.zeros(2), crank_motion)
    pivot_d = np.array([g.ground, 0.0])
    fixed_d = (pivot_d, np.zeros(2), np.zeros(2))
    coupler_m, rocker_m = _dyad(_tip_motion(crank), fixed_d, (g.coupler, g.rocker), elbow_up, inputs[0])
    coupler = _hinged("coupler", g.bar(g.coupler), crank, coupler_m)
    rocker = _grounded("rocker", g.bar(g.rocker), pivot_d, rocker_m)
    joints = (
        PlanarJoint("crank", None, "crank", np.zeros(2), actuated=True),
        PlanarJoint("coupler", "crank", "coupler", crank.tip),
        PlanarJoint("rocker", None, "rocker", pivot_d),
        PlanarJoint("C", "coupler", "rocker", rocker.tip),
    )
    coords = np.column_stack([crank_motion, _relative(coupler_m, crank_motion), rocker_m])
    links = {link.name: link for link in (crank, coupler, rocker)}
    return LinkageState(links, joints, ("crank", "coupler", "rocker"), *coords)


def five_bar(
    thetas: tuple[float, float],
    rates: tuple[float, float] = (0.0, 0.0),
    accelerations: tuple[float, float] = (0.0, 0.0),
    geometry: FiveBarGeometry = FiveBarGeometry(),
    elbow_up: bool = True,
) -> LinkageState:
    """Exact motion of the five-bar from both proximal angles and their two derivatives.

    Joints: "prox1" at A1 = (0, 0) and "prox2" at A2 = (ground, 0) (ground -> proximal, actuated),
    "dist1" / "dist2" at the proximal tips B1 / B2 (proximal -> distal, relative angles), loop cut
    "C" (dist1 tip, parent side, meets dist2 tip). q = [theta1, phi1, theta2, phi2].

    Args:
        thetas: (theta1, theta2) proximal angles, rad. rates: rad/s. accelerations: rad/s^2.
        geometry: lengths and bar section.
        elbow_up: C on the larger-z branch; False for the other.

    Raises:
        InvalidParameters: non-finite input or input angles at which the linkage cannot assemble.
        SingularConfiguration: the distal bars collinear.
    """
    g = geometry
    inputs = (("thetas", thetas), ("rates", rates), ("accelerations", accelerations))
    motions = [tuple(_finite(f"{n}[{i}]", v[i]) for n, v in inputs) for i in (0, 1)]
    prox1 = _grounded("prox1", g.bar(g.prox1), np.zeros(2), motions[0])
    prox2 = _grounded("prox2", g.bar(g.prox2), np.array([g.ground, 0.0]), motions[1])
    lengths = (g.dist1, g.dist2)
    tips = _tip_motion(prox1), _tip_motion(prox2)
    dist1_m, dist2_m = _dyad(*tips, lengths, elbow_up, ("thetas", tuple(thetas)))
    dist1 = _hinged("dist1", g.bar(g.dist1), prox1, dist1_m)
    dist2 = _hinged("dist2", g.bar(g.dist2), prox2, dist2_m)
    joints = (
        PlanarJoint("prox1", None, "prox1", prox1.origin, actuated=True),
        PlanarJoint("dist1", "prox1", "dist1", prox1.tip),
        PlanarJoint("prox2", None, "prox2", prox2.origin, actuated=True),
        PlanarJoint("dist2", "prox2", "dist2", prox2.tip),
        PlanarJoint("C", "dist1", "dist2", dist1.tip),
    )
    coords = np.column_stack(
        [motions[0], _relative(dist1_m, motions[0]), motions[1], _relative(dist2_m, motions[1])]
    )
    links = {link.name: link for link in (prox1, dist1, prox2, dist2)}
    return LinkageState(links, joints, ("prox1", "dist1", "prox2", "dist2"), *coords)


def newton_euler(state: LinkageState, gravity: np.ndarray = np.array([0.0, 0.0, -9.81])) -> PlanarDynamics:
    """Per-link planar Newton-Euler: every pin force and every actuator torque.

    Per link: m a_c = m g + sum of pin forces on it; I alpha = sum of their moments about the COM
    + motor torques on it (planar, counter-clockwise = about -y). The linkage must be statically
    determinate in the plane (3 equations per link = 2 per pin + 1 per actuator).

    Args:
        state: the linkage's motion.
        gravity: (3,) m/s^2, world, in the x-z plane.

    Returns:
        Efforts and world reaction wrenches, see :class:`PlanarDynamics`.

    Raises:
        InvalidParameters: gravity out of the plane, or a linkage that is not statically determinate.
        SingularConfiguration: the Newton-Euler system is singular.
    """
    gravity = np.asarray(gravity, dtype=float)
    if gravity.shape != (3,) or gravity[1] != 0.0 or not np.all(np.isfinite(gravity)):
        raise InvalidParameters("gravity", gravity, "must be a finite (3,) vector in the x-z plane")
    links = list(state.links.values())
    row = {link.name: 3 * i for i, link in enumerate(links)}
    actuated = [j.name for j in state.joints if j.actuated]
    n_unknowns = 2 * len(state.joints) + len(actuated)
    if n_unknowns != 3 * len(links):
        why = f"{n_unknowns} unknown pin forces and torques for {3 * len(links)} planar equations"
        raise InvalidParameters("state.joints", [j.name for j in state.joints], why)
    a = np.zeros((n_unknowns, n_unknowns))
    for k, joint in enumerate(state.joints):
        for side, sign in ((joint.parent, -1.0), (joint.child, 1.0)):
            if side is None:
                continue
            r = joint.point - state.links[side].com
            i = row[side]
            a[i : i + 2, 2 * k : 2 * k + 2] += sign * np.eye(2)
            a[i + 2, 2 * k : 2 * k + 2] += sign * np.array([-r[1], r[0]])  # planar r x F
            if joint.actuated:
                a[i + 2, 2 * len(state.joints) + actuated.index(joint.name)] += sign
    b = np.zeros(n_unknowns)
    for link in links:
        i = row[link.name]
        b[i : i + 2] = link.bar.mass * (link.com_acceleration - gravity[[0, 2]])
        b[i + 2] = link.bar.inertia_planar * link.alpha
    sv = np.linalg.svd(a, compute_uv=False)
    if sv[-1] <= RANK_TOL * sv[0]:
        cond = np.inf if sv[-1] == 0.0 else float(sv[0] / sv[-1])
        raise SingularConfiguration(cond, "planar Newton-Euler system")
    x = np.linalg.solve(a, b)
    efforts = {name: float(x[2 * len(state.joints) + i]) for i, name in enumerate(actuated)}
    reactions = {}
    for k, joint in enumerate(state.joints):
        force = x[2 * k : 2 * k + 2]
        moment = -efforts[joint.name] if joint.actuated else 0.0  # motor torque about -y
        reactions[joint.name] = np.array([force[0], 0.0, force[1], 0.0, moment, 0.0])
    return PlanarDynamics(efforts, reactions, float(sv[0] / sv[-1]))
