"""Parameters of the 2-DOF spherical platform (Zhang et al. 2016): the paper's arcs and azimuths, our sizes.

Angles in rad, lengths in m. The structural angles (alpha*, beta*, eta*) are those of
`spherical_2dof.kinematics`; the sizes and masses (marked ours) are not in the paper.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.params import MechanismParams, param
from mechkit.mechanisms.spherical_2dof import kinematics as kin

__all__ = ["Spherical2DofParams"]


@dataclass(frozen=True)
class Spherical2DofParams(MechanismParams):
    """Link arcs and axis angles (rad), sizes (m) and masses of the 2-DOF spherical platform."""

    alpha1: float = param(math.radians(25.0), "rad", "arc between the motor axis u_i and the middle axis w_i")
    alpha2: float = param(math.radians(30.0), "rad", "arc between the middle axis w_i and the platform axis v_i")
    beta: float = param(math.radians(53.13), "rad", "angle of the motor axes u_i from -Z0 (eq. 5)")
    beta_platform: float = param(
        math.radians(90.0),
        "rad",
        "angle of the platform axes v_i from -Z (absent from the paper; 90 deg: in the platform plane)",
        ours=True,
    )
    eta11: float = param(0.0, "rad", "base azimuth of limb 1's motor axis u_1 (the reference: 0 by definition of X0)")
    eta12: float = param(math.radians(90.0), "rad", "base azimuth of limb 2's motor axis u_2 from u_1")
    eta21: float = param(
        0.0, "rad", "platform azimuth of limb 1's platform axis v_1 (the reference: 0 by definition of X)"
    )
    eta22: float = param(math.radians(90.0), "rad", "platform azimuth of limb 2's platform axis v_2 from v_1")
    radius: float = param(0.12, "m", "sphere radius of the limb links (joint points)", ours=True)
    link_width: float = param(0.02, "m", "square section side of the limb links", ours=True)
    density: float = param(2700.0, "kg/m^3", "aluminium limb links", ours=True)
    platform_mass: float = param(2.0, "kg", "platform with its isolated payload", ours=True)
    platform_radius: float = param(0.15, "m", "platform disc radius", ours=True)
    platform_thickness: float = param(0.01, "m", "platform disc thickness", ours=True)
    platform_height: float = param(0.05, "m", "platform centre of mass above O along its normal", ours=True)
    cross_mass: float = param(0.1, "kg", "Hooke-joint cross (a cube at O)", ours=True)
    cross_size: float = param(0.03, "m", "Hooke-joint cross cube side", ours=True)
    rows: str = param(
        "spherical",
        "-",
        "closure rows per cut: spherical (2 rotation rows) or spatial (5, 3 of them redundant)",
    )

    def validate(self) -> None:
        """Rows known, link arcs in (0, 90) deg, and both limbs assemble at home.

        Raises:
            InvalidParameters: one of them fails.
        """
        if self.rows not in ("spherical", "spatial"):
            raise InvalidParameters("rows", self.rows, "one of 'spherical', 'spatial'")
        for name in ("alpha1", "alpha2"):
            if not 0.0 < getattr(self, name) < math.pi / 2:
                raise InvalidParameters(name, getattr(self, name), "a link arc must lie in (0, 90) deg")
        lo, hi = abs(self.alpha1 - self.alpha2), self.alpha1 + self.alpha2
        for i in (1, 2):
            arc = math.acos(float(np.clip(kin.base_axis(self, i) @ kin.platform_axis(self, i, (0.0, 0.0)), -1, 1)))
            if not lo < arc < hi:
                why = (
                    f"limb {i} cannot assemble at home: the u-v arc {math.degrees(arc):.2f} deg is outside "
                    f"(|alpha1 - alpha2|, alpha1 + alpha2) = ({math.degrees(lo):.2f}, {math.degrees(hi):.2f}) deg"
                )
                raise InvalidParameters("beta_platform", self.beta_platform, why)
