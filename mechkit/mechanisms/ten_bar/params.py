"""Ten-bar under-actuated solar-array deployment linkage (patent CN105975733, Radarsat-2).

Topology (the patent's): the satellite side wall l1,5 holds R1 and R5; 9 moving links l1,2,3 (panel
1, with R10 welded on it), l3,4 (panel 2), l4,8, l8,7, l6,7, l5,6, l2,7, l7,9, l9,10; hinges R1..R10
with R7 a compound hinge of four links (three pairs), 12 revolute pairs, DOF = 3*9 - 2*12 = 3.
Loops: five-bar (wall, l123, l27, l67, l56; DOF 2), four-bar (l123, l27, l79, l910), six-bar
(l123, l34, l48, l87, l79, l910). Motors at R1 (panel 1 on the wall) and R3 (panel 2 on panel 1);
the third DOF, in the five-bar, is passive and driven by a torsion spring at R5, as the patent's
elastic elements drive the real hinges.

The patent gives no dimension. The design below is ours (geometry in `ten_bar_geometry`):

- Panels: 1.2 m x 1.0 m rigid panels at 2.5 kg/m^2 (honeycomb substrate with cells, the usual
  2-3 kg/m^2), 3.0 kg each. Stowed (t = 0): panel 1 stands up along the wall (R1 angle pi/2),
  panel 2 folded back down on it (R3 angle -pi). Deployed: R1 = 0 and R3 = 0, l2,3 and l3,4
  collinear along +x, perpendicular to the wall.
- Every loop is sized with Grashof-type margins so that it closes for EVERY value of its inputs,
  not only along one planned path: the wall rocker R5-R6 (0.08 m) and the arm R1-R2 (0.117 m) are
  short against the wall gap (0.5 m), and |l67 - l27| = 0.25 < 0.5 - 0.117 - 0.08 while
  l67 + l27 = 0.75 > 0.5 + 0.117 + 0.08, so the five-bar closes for any (R1, R5); in panel 1's
  frame l27 (0.25) turns fully inside the four-bar (ground R2-R10 0.667, l79 + l910 = 1.13 >
  0.917, |l910 - l79| = 0.13 < 0.417); the dyad l48-l87 (0.9 + 0.9) spans every distance R4-R7
  can take (0.75..1.65 m). The passive DOF, which only the dynamics decides, can therefore never
  jam the linkage, and no loop meets a dead-centre pose: `Pose.margins` (sine of the angle at the
  closing hinge) stays >= 0.47 for every motor and rocker angle, >= 0.66 over the deployment.
- Branches: the three circle intersections take the side that keeps every hinge outside the wall
  (x > 0) over the deployment.
- Links: aluminium bars 25 mm x 10 mm (0.675 kg/m). The spring at R5 (4 N m/rad, 5.4 N m preload
  at the stowed angle, free angle +17.4 degrees, and a viscous damper as real deployment hinges
  carry) swings the rocker l56 from -60 degrees (stowed) within 0.2 s to about +2 degrees, where
  it balances the linkage's weight (about 1.2 N m on R5); it then follows the slowly changing
  balance (-4..+9 degrees) while the motors deploy the panels over 20 s. With 0.008-0.009 kg m^2
  of effective inertia on R5 its natural frequency (about 21 rad/s) sits well above the motor
  laws' and the damper (ratio about 0.8) keeps it from ringing.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass

import numpy as np

from mechkit.description import LOOP_NAMESPACE
from mechkit.exceptions import InvalidParameters, MalformedDescription
from mechkit.mechanisms import ten_bar_geometry as geo
from mechkit.params import MechanismParams, param
from mechkit.contract import MechanismSpec
from mechkit.validation import lagrange

STOWED = {"R1": math.pi / 2, "R3": -math.pi}
"""Motor angles stowed: panel 1 up along the wall, panel 2 folded back on it (rad)."""
DEPLOYED = {"R1": 0.0, "R3": 0.0}
"""Motor angles deployed: both panels along +x, perpendicular to the wall (rad)."""
MOTORS = ("R1", "R3")
PASSIVE = "R5"


@dataclass(frozen=True)
class TenBarParams(MechanismParams):
    wall_gap: float = param(0.5, "m", "R1-R5 on the wall (R5 below R1)", ours=True)
    r2_along: float = param(0.06, "m", "R2 from R1 along panel 1's axis", ours=True, positive=False)
    r2_normal: float = param(
        -0.10,
        "m",
        "R2 from R1 normal to panel 1's axis (negative: away from the wall when stowed)",
        ours=True,
        positive=False,
    )
    panel1: float = param(1.2, "m", "l2,3: panel 1 length, R2-R3", ours=True)
    r10_along: float = param(0.65, "m", "R10 from R2 along panel 1's axis", ours=True, positive=False)
    r10_normal: float = param(-0.15, "m", "R10 from R2 normal to panel 1's axis", ours=True, positive=False)
    l34: float = param(0.2, "m", "l3,4: R3-R4 on panel 2's axis", ours=True)
    panel2: float = param(1.2, "m", "panel 2 length from R3", ours=True)
    l56: float = param(0.08, "m", "l5,6: wall rocker", ours=True)
    l67: float = param(0.5, "m", "l6,7", ours=True)
    l27: float = param(0.25, "m", "l2,7", ours=True)
    l79: float = param(0.5, "m", "l7,9", ours=True)
    l910: float = param(0.63, "m", "l9,10", ours=True)
    l48: float = param(0.9, "m", "l4,8", ours=True)
    l87: float = param(0.9, "m", "l8,7", ours=True)
    panel_width: float = param(1.0, "m", "panel size along the hinge axes", ours=True)
    panel_thickness: float = param(0.02, "m", "panel thickness", ours=True)
    panel_areal_density: float = param(2.5, "kg/m^2", "rigid panel with cells", ours=True, positive=True)
    rod_width: float = param(0.025, "m", "bar size in the plane", ours=True)
    rod_thickness: float = param(0.01, "m", "bar size along the axes", ours=True)
    rod_density: float = param(2700.0, "kg/m^3", "aluminium", ours=True)
    stowed_rocker: float = param(-math.pi / 3, "rad", "R5 angle of l5,6 when stowed", ours=True)
    spring_stiffness: float = param(4.0, "N m/rad", "torsion spring at R5", ours=True, positive=True)
    spring_preload: float = param(5.4, "N m", "spring torque at the stowed angle (towards +R5)", ours=True)
    spring_damping: float = param(0.3, "N m s/rad", "viscous damper at R5", ours=True)
    deploy_time: float = param(20.0, "s", "duration of the motor laws", ours=True, positive=True)
    rows: str = param("planar", "-", "closure rows: planar (2 per pin) or spatial (5 per pin)")

    def validate(self) -> None:
        if self.spring_damping < 0:
            raise InvalidParameters("spring_damping", self.spring_damping, "must be >= 0")
        reach = math.hypot(self.r2_along, self.r2_normal) + self.l56
        if (
            not abs(self.l67 - self.l27) < self.wall_gap - reach
            or not self.l67 + self.l27 > self.wall_gap + reach
        ):
            raise InvalidParameters(
                "l27/l67",
                (self.l27, self.l67),
                f"the five-bar must close for every motor and rocker angle: need |l67 - l27| < "
                f"{self.wall_gap - reach:.4f} m < {self.wall_gap + reach:.4f} m < l67 + l27",
            )


def spring(p: TenBarParams) -> lagrange.Spring:
    """The R5 torsion spring-damper: torque = preload - k (angle - stowed) - c rate on l56."""
    return lagrange.Spring(
        PASSIVE, p.spring_stiffness, p.stowed_rocker + p.spring_preload / p.spring_stiffness, p.spring_damping
    )


def spring_from_urdf(urdf: str) -> lagrange.Spring:
    """Read the `<mechkit:spring>` element of the URDF (the xacro's spring arguments).

    Raises:
        MalformedDescription: no spring element, or one without its attributes.
    """
    element = ET.fromstring(urdf).find(f"{{{LOOP_NAMESPACE}}}spring")
    if element is None:
        raise MalformedDescription("mechkit:spring", "the ten-bar URDF declares no spring")
    try:
        k, pre, ref = (float(element.attrib[a]) for a in ("stiffness", "preload", "reference"))
        return lagrange.Spring(
            element.attrib["joint"], k, ref + pre / k, float(element.attrib.get("damping", 0.0))
        )
    except (KeyError, ValueError) as err:
        raise MalformedDescription("mechkit:spring", f"bad attribute: {err}") from None


def motor_law(p: TenBarParams, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cycloidal motor laws stowed -> deployed over `deploy_time` (zero rate and acceleration at both ends).

    Returns (angles, rates, accelerations) of (R1, R3): rad, rad/s, rad/s^2.
    """
    T = p.deploy_time
    s = min(max(t / T, 0.0), 1.0)
    inside = 0.0 < t / T < 1.0
    shape = s - math.sin(2 * math.pi * s) / (2 * math.pi)
    rate = (1 - math.cos(2 * math.pi * s)) / T if inside else 0.0
    acc = 2 * math.pi * math.sin(2 * math.pi * s) / T**2 if inside else 0.0
    delta = np.array([DEPLOYED[m] - STOWED[m] for m in MOTORS])
    start = np.array([STOWED[m] for m in MOTORS])
    return start + delta * shape, delta * rate, delta * acc


def stowed_pose(p: TenBarParams) -> geo.Pose:
    """Closed-form stowed assembly."""
    return geo.pose(p, STOWED["R1"], STOWED["R3"], p.stowed_rocker)


def lagrange_linkage(p: TenBarParams, spring_: lagrange.Spring | None = None) -> lagrange.Linkage:
    """The patent's Lagrange first-kind model of the ten-bar, from the parameters (numpy only)."""
    props = geo.mass_properties(p)
    index = {b: i for i, b in enumerate(geo.BODIES)}
    bodies = [lagrange.Body(b, props[b][0], props[b][2], props[b][1]) for b in geo.BODIES]
    pins = [
        lagrange.Pin(
            h.name,
            None if h.parent is None else index[h.parent],
            h.parent_point,
            index[h.child],
            h.child_point,
        )
        for h in geo.hinges(p)
    ]
    return lagrange.Linkage(bodies, pins, MOTORS, (spring_ or spring(p),))


def lagrange_coordinates(p: TenBarParams, pose: geo.Pose) -> np.ndarray:
    """Reference-point coordinates (COM x, z, absolute angle per link) of a closed-form pose."""
    props = geo.mass_properties(p)
    h = geo.hinge_points(p)
    q = np.empty(3 * len(geo.BODIES))
    for i, body in enumerate(geo.BODIES):
        phi = pose.angles[body]
        origin_hinge = next(iter(h[body]))  # each body frame's origin is its first hinge
        q[3 * i : 3 * i + 2] = pose.points[origin_hinge] + geo.rot(phi) @ props[body][1]
        q[3 * i + 2] = phi
    return q


class TreeKinematics:
    """Numpy forward kinematics of the spanning tree: joint angles -> reference-point coordinates.

    Joints in `ten_bar_geometry.TREE_JOINTS` order; the rates may
    be a (9,) vector or a (9, k) matrix (k rate vectors at once: with the identity, the columns of
    d q_L / d theta).
    """

    def __init__(self, p: TenBarParams):
        props = geo.mass_properties(p)
        index = {b: i for i, b in enumerate(geo.BODIES)}
        self.steps = [
            (None if h.parent is None else index[h.parent], h.parent_point, index[h.child])
            for h in geo.hinges(p)[: len(geo.TREE_JOINTS)]
        ]
        self.coms = [props[b][1] for b in geo.BODIES]

    def __call__(self, angles: np.ndarray, rates: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(q_L (27,), qd_L (27,) or (27, k)) from tree-joint angles and rates (rad, rad/s)."""
        rates = np.asarray(rates, dtype=float)
        shape = rates.shape[1:]
        n = len(self.coms)
        origin, origin_rate = np.zeros((n, 2)), np.zeros((n, 2) + shape)
        phi, omega = np.zeros(n), np.zeros((n,) + shape)
        for k, (parent, point, child) in enumerate(self.steps):
            if parent is None:
                arm, o, od, ph, w = point, np.zeros(2), np.zeros((2,) + shape), 0.0, np.zeros(shape)
            else:
                ph, w = phi[parent], omega[parent]
                arm = geo.rot(ph) @ point
                o, od = origin[parent], origin_rate[parent]
            origin[child] = o + arm
            origin_rate[child] = od + np.multiply.outer([-arm[1], arm[0]], w)
            phi[child] = ph + angles[k]
            omega[child] = w + rates[k]
        q, qd = np.empty(3 * n), np.empty((3 * n,) + shape)
        for i, com in enumerate(self.coms):
            c = geo.rot(phi[i]) @ com
            q[3 * i : 3 * i + 3] = [*(origin[i] + c), phi[i]]
            qd[3 * i : 3 * i + 2] = origin_rate[i] + np.multiply.outer([-c[1], c[0]], omega[i])
            qd[3 * i + 2] = omega[i]
        return q, qd


def lagrange_from_joints(
    p: TenBarParams, angles: dict[str, float], rates: dict[str, float]
) -> tuple[np.ndarray, np.ndarray]:
    """Reference-point coordinates and rates from tree-joint angles and rates (numpy forward kinematics)."""
    fk = TreeKinematics(p)
    return fk(np.array([angles[j] for j in geo.TREE_JOINTS]), np.array([rates[j] for j in geo.TREE_JOINTS]))


def joint_angles_from_lagrange(q: np.ndarray) -> dict[str, float]:
    """URDF tree-joint values from reference-point coordinates (relative absolute angles, rad)."""
    return geo.relative_angles({b: q[3 * i + 2] for i, b in enumerate(geo.BODIES)})


def _home(p: TenBarParams) -> dict[str, float]:
    return {**STOWED, PASSIVE: p.stowed_rocker}


def _guess(p: TenBarParams) -> dict[str, float]:
    return stowed_pose(p).joint_angles()


def _self_checks(mechanism) -> dict[str, float]:
    from mechkit.mechanisms.ten_bar_checks import self_checks

    return self_checks(mechanism)


SPEC = MechanismSpec(
    name="ten_bar",
    params=TenBarParams,
    template="ten_bar.urdf.xacro",
    actuated=MOTORS,
    gruebler_dof=3,
    home=_home,
    guess=_guess,
    summary="Radarsat-2 solar-array ten-bar (patent CN105975733): 9 links, 12 pairs, 2 motors + 1 spring DOF",
    self_checks=_self_checks,
)


def deployment_poses(mechanism, frames: int = 120, dt: float = 0.02) -> list[np.ndarray]:
    """Stowed to deployed: the constrained-ABA deployment (RK4 with projection, step dt in s) sampled
    at `frames` poses, for animations."""
    from mechkit.mechanisms import ten_bar_dynamics as td

    trajectory = td.deploy(td.PinocchioDeployment(mechanism), mechanism.home_q, dt)
    picks = np.linspace(0, len(trajectory.q) - 1, frames).round().astype(int)
    return [trajectory.q[i] for i in picks]


SCENES = {"deploy": deployment_poses}
