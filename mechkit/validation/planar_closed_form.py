"""Closed-form kinematics of the calibration four-bar and five-bar (numpy only).

Exact: circle intersection for positions, exact linear solves of the differentiated loop equation
for rates and accelerations. Conventions (plane x-z, axes along -y, bars along their local x) are
those of `mechkit.validation.planar_motion`; the result is a `LinkageState` with every link's
motion and every pin, the loop cut "C" included.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.validation.planar_motion import Bar, LinkageState, LinkState, PlanarJoint, perp
from mechkit.validation.soc import RANK_TOL

__all__ = ["FiveBarGeometry", "FourBarGeometry", "five_bar", "four_bar"]


def _wrap(angle: float) -> float:
    """Angle in (-pi, pi]."""
    return float(np.pi - np.mod(np.pi - angle, 2.0 * np.pi))


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
    c = pp + along * d_hat + (1.0 if elbow_up else -1.0) * np.sqrt(lu**2 - along**2) * perp(d_hat)
    eu, ev = (c - pp) / lu, (c - pq) / lv
    matrix = np.column_stack([lu * perp(eu), -lv * perp(ev)])
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
        theta: crank angle, rad.
        rate: its rate, rad/s.
        acceleration: its acceleration, rad/s^2.
        geometry: lengths and bar section.
        elbow_up: C on the open (larger z) branch; False for the crossed one.

    Returns:
        The linkage's state: every link's motion and every pin, q, qd and qdd.

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
        thetas: (theta1, theta2) proximal angles, rad.
        rates: their rates, rad/s.
        accelerations: their accelerations, rad/s^2.
        geometry: lengths and bar section.
        elbow_up: C on the larger-z branch; False for the other.

    Returns:
        The linkage's state: every link's motion and every pin, q, qd and qdd.

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
    coords = np.column_stack([motions[0], _relative(dist1_m, motions[0]), motions[1], _relative(dist2_m, motions[1])])
    links = {link.name: link for link in (prox1, dist1, prox2, dist2)}
    return LinkageState(links, joints, ("prox1", "dist1", "prox2", "dist2"), *coords)
