"""Parameters of the engine gimbal (Qian et al., reference 004), the pivot geometry and the bodies' inertias.

Lengths in m, masses in kg. From the paper: the actuator lengths at zero stroke. Ours (marked so): the
pivot coordinates (a reconstruction that reproduces the paper's printed numbers), every mass and
inertia, the actuator dimensions.
"""

from __future__ import annotations

from dataclasses import dataclass

from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.params import MechanismParams, param
from mechkit.mechanisms.rocket_gimbal.kinematics import RULE_STROKE, GimbalGeometry

__all__ = ["BodySpec", "RocketGimbalParams", "body_inertias", "geometry"]

BodySpec = dict[str, tuple[float, float, float]]
"""Body name -> (mass kg, transverse and axial moments of inertia about the COM, kg m^2)."""


@dataclass(frozen=True)
class RocketGimbalParams(MechanismParams):
    """Pivot layout (m), actuator lengths (m) and the masses and inertias of the engine gimbal."""

    pivot_radius: float = param(
        1.009116,
        "m",
        "r: distance of the actuator lines from the nozzle axis (reconstruction reproducing the paper's IK example)",
        ours=True,
    )
    pivot_offset: float = param(
        0.69511,
        "m",
        "h: engine pivots' distance from O along the nozzle axis, towards the nozzle (reconstruction)",
        ours=True,
    )
    length_a: float = param(1.843, "m", "lA0, actuator A length at zero stroke (paper)")
    length_b: float = param(1.843, "m", "lB0, actuator B length at zero stroke (paper)")
    engine_mass: float = param(2000.0, "kg", "YF-100 class kerosene/LOX engine (about 1.2 MN, ~2 t)", ours=True)
    engine_com: float = param(1.2, "m", "engine COM on the nozzle axis, from O", ours=True)
    engine_length: float = param(3.0, "m", "engine envelope length (uniform solid cylinder inertia)", ours=True)
    engine_radius: float = param(0.6, "m", "engine envelope radius", ours=True)
    bracket_mass: float = param(80.0, "kg", "moving bracket (thin ring inertia)", ours=True)
    bracket_radius: float = param(0.35, "m", "moving bracket ring radius", ours=True)
    cylinder_mass: float = param(45.0, "kg", "servo cylinder body (frame side)", ours=True)
    cylinder_length: float = param(1.1, "m", "servo cylinder length from the frame pivot", ours=True)
    rod_mass: float = param(15.0, "kg", "servo piston rod (engine side)", ours=True)
    rod_length: float = param(1.1, "m", "piston rod length back from the engine pivot", ours=True)
    actuator_radius: float = param(0.06, "m", "servo cylinder radius (rod: half)", ours=True)
    cross_mass: float = param(2.0, "kg", "Hooke cross at a frame pivot (COM at the pivot)", ours=True)
    cross_inertia: float = param(0.004, "kg m^2", "Hooke cross moment of inertia (isotropic)", ours=True)

    def validate(self) -> None:
        """Rod and cylinder shorter than the shortest actuator, overlapping at full stroke; frame pivots off O's plane.

        Raises:
            InvalidParameters: one of them fails.
        """
        shortest = min(self.length_a, self.length_b) - RULE_STROKE
        if self.rod_length >= shortest or self.cylinder_length >= shortest:
            raise InvalidParameters(
                "rod_length/cylinder_length",
                (self.rod_length, self.cylinder_length),
                f"each must be shorter than the shortest actuator length {shortest:.3f} m",
            )
        if self.cylinder_length + self.rod_length <= max(self.length_a, self.length_b) + RULE_STROKE:
            raise InvalidParameters(
                "rod_length/cylinder_length",
                (self.rod_length, self.cylinder_length),
                "rod and cylinder must overlap at full stroke",
            )
        if abs(self.pivot_offset - self.length_a) < 1e-6 or abs(self.pivot_offset - self.length_b) < 1e-6:
            raise InvalidParameters(
                "pivot_offset",
                self.pivot_offset,
                "frame pivots coplanar with O: the paper's mechanism has them off the plane",
            )


def geometry(p: RocketGimbalParams) -> GimbalGeometry:
    """The pivots of the paper frame O-xyz from the parameters.

    Args:
        p: the parameters.

    Returns:
        The geometry.
    """
    return GimbalGeometry.reconstruction(p.pivot_radius, p.pivot_offset, p.length_a, p.length_b)


def body_inertias(p: RocketGimbalParams) -> BodySpec:
    """Mass (kg) and transverse / axial moments of inertia about the COM (kg m^2) of each moving body.

    Every body is axisymmetric: the engine and the servo parts are uniform solid cylinders about their
    axes, the bracket a thin ring about its normal, the Hooke crosses isotropic. The xacro computes the
    same from the same numbers.

    Args:
        p: the parameters.

    Returns:
        Body -> (mass kg, transverse moment kg m^2, axial moment kg m^2).
    """

    def cylinder(mass: float, length: float, radius: float) -> tuple[float, float, float]:
        return mass, mass * (3.0 * radius**2 + length**2) / 12.0, mass * radius**2 / 2.0

    ring = p.bracket_mass * p.bracket_radius**2
    out = {
        "engine": cylinder(p.engine_mass, p.engine_length, p.engine_radius),
        "bracket": (p.bracket_mass, ring / 2.0, ring),
    }
    for name in "ab":
        out[f"{name}_cylinder"] = cylinder(p.cylinder_mass, p.cylinder_length, p.actuator_radius)
        out[f"{name}_rod"] = cylinder(p.rod_mass, p.rod_length, p.actuator_radius / 2.0)
        out[f"{name}_cross"] = (p.cross_mass, p.cross_inertia, p.cross_inertia)
    return out
