"""Ten-bar parameters and actuation: the design's dataclass, the motor laws and the R5 spring.

The design (dimensions, masses, the spring's sizing) is described in the package docstring
(`mechkit.mechanisms.ten_bar`). The spring can be built from the parameters (`spring`) or read back
from the generated URDF's `<mechkit:spring>` element (`spring_from_urdf`), which is what the
Pinocchio route uses.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidParameters, MalformedDescription
from mechkit.catalog.params import MechanismParams, param
from mechkit.sources.urdf import parse_springs
from mechkit.validation import lagrange

STOWED = {"R1": math.pi / 2, "R3": -math.pi}
"""Motor angles stowed: panel 1 up along the wall, panel 2 folded back on it (rad)."""
DEPLOYED = {"R1": 0.0, "R3": 0.0}
"""Motor angles deployed: both panels along +x, perpendicular to the wall (rad)."""
MOTORS = ("R1", "R3")
"""The actuated joints: panel 1 on the wall, panel 2 on panel 1."""
PASSIVE = "R5"
"""The spring-driven joint (wall rocker l5,6), the passive DOF."""


@dataclass(frozen=True)
class TenBarParams(MechanismParams):
    """The ten-bar's parameters (every field is a xacro argument); the design is the package docstring's."""

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
        """Damping >= 0 and the five-bar closes for every motor and rocker angle.

        Raises:
            InvalidParameters: one of them fails.
        """
        if self.spring_damping < 0:
            raise InvalidParameters("spring_damping", self.spring_damping, "must be >= 0")
        reach = math.hypot(self.r2_along, self.r2_normal) + self.l56
        if not abs(self.l67 - self.l27) < self.wall_gap - reach or not self.l67 + self.l27 > self.wall_gap + reach:
            raise InvalidParameters(
                "l27/l67",
                (self.l27, self.l67),
                f"the five-bar must close for every motor and rocker angle: need |l67 - l27| < "
                f"{self.wall_gap - reach:.4f} m < {self.wall_gap + reach:.4f} m < l67 + l27",
            )


def spring(p: TenBarParams) -> lagrange.Spring:
    """The R5 torsion spring-damper: torque = preload - k (angle - stowed) - c rate on l56.

    Args:
        p: the ten-bar's parameters.

    Returns:
        The Lagrange model's spring.
    """
    return lagrange.Spring(
        PASSIVE, p.spring_stiffness, p.stowed_rocker + p.spring_preload / p.spring_stiffness, p.spring_damping
    )


def spring_from_urdf(urdf: str) -> lagrange.Spring:
    """The `<mechkit:spring>` of the URDF (the xacro's spring arguments, `sources.urdf.parse_springs`) as
    the Lagrange model's spring: torque = stiffness (free angle - q) - damping qdot.

    Args:
        urdf: the ten-bar's URDF text.

    Returns:
        The spring.

    Raises:
        MalformedDescription: no spring element, or a malformed one.
    """
    springs = parse_springs(urdf)
    if not springs:
        raise MalformedDescription("mechkit:spring", "the ten-bar URDF declares no spring")
    s = springs[0]
    return lagrange.Spring(s.joint, s.stiffness, s.reference + s.preload / s.stiffness, s.damping)


def motor_law(p: TenBarParams, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cycloidal motor laws stowed -> deployed over `deploy_time` (zero rate and acceleration at both ends).

    Returns (angles, rates, accelerations) of (R1, R3): rad, rad/s, rad/s^2.

    Args:
        p: the ten-bar's parameters.
        t: time, s.

    Returns:
        (angles, rates, accelerations) of (R1, R3): rad, rad/s, rad/s^2.
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
