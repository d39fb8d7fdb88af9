"""The 2T1R's parameters (dimensions of reference 001, our links and payload), mass properties and motors.

Actuation: R11, R21, R31 (theta_1..theta_3). With ``redundant_actuation=True`` R41 (theta_4) is
driven too: four motors for three degrees of freedom; the efforts are then fixed only up to the
mechanism's null space, and mechkit's validators use the minimum-norm distribution (see
`soc.classic_torques`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.params import MechanismParams, param
from mechkit.mechanisms.parallel_2t1r.branch import EXAMPLE_INPUTS, assembled_pose
from mechkit.mechanisms.parallel_2t1r.kinematics import BODIES, Dims


@dataclass(frozen=True)
class Parallel2T1RParams(MechanismParams):
    """Dimensions (m), bar sections and material, payload of the 2T1R parallel mechanism."""

    l1: float = param(0.4, "m", "side of the base square A1A2A3A4 (paper: 400 mm)")
    l2: float = param(0.2, "m", "length of every limb link (paper: 200 mm)")
    l3: float = param(0.462, "m", "platform side C3C4 (paper: 462 mm)")
    bar_width: float = param(0.025, "m", "link cross-section, in the plane of motion", ours=True)
    bar_thickness: float = param(0.012, "m", "link cross-section, along the axes", ours=True)
    density: float = param(2700.0, "kg/m^3", "aluminium links and plate", ours=True)
    plate_thickness: float = param(0.01, "m", "platform plate (triangle C1 C3 C4)", ours=True)
    payload_mass: float = param(5.0, "kg", "payload cube at the platform centroid (a tool head)", ours=True)
    payload_size: float = param(0.1, "m", "side of the payload cube", ours=True)
    redundant_actuation: bool = param(False, "-", "drive R41 too (four motors for three DOF)")

    def validate(self) -> None:
        """The platform within the limbs' reach, bars narrower than l2, the paper's example inputs assemble.

        Raises:
            InvalidParameters: one of them fails.
        """
        if self.l3 / 2.0 >= self.l1 + self.l2:
            raise InvalidParameters("l3", self.l3, "platform wider than the limbs can hold")
        if self.l2 <= self.bar_width:
            raise InvalidParameters("bar_width", self.bar_width, "must be smaller than the link length l2")
        try:  # the home assembly: the paper's example inputs on the assembled branch
            assembled_pose(self.dims, EXAMPLE_INPUTS)
        except InvalidParameters as err:
            why = f"the example inputs (10, 20, 30 deg) do not assemble: {err.why}"
            raise InvalidParameters("l1, l2, l3", (self.l1, self.l2, self.l3), why) from None

    @property
    def dims(self) -> Dims:
        """The dimensions (m) the analytic kinematics take."""
        return Dims(self.l1, self.l2, self.l3)


def mass_properties(p: Parallel2T1RParams) -> dict[str, tuple[float, np.ndarray, np.ndarray]]:
    """Mass (kg), COM (3,) m and inertia (3, 3) kg m^2 about the COM, in each body's own frame.

    Bars: local x along the link from its joint, box inertia; platform: frame at C1, x = u, y = v,
    triangular plate (height l1 between the limb planes) plus the payload cube at the centroid.
    The same numbers as the xacro template (a test compares them with the URDF).

    Args:
        p: the parameters.

    Returns:
        Body -> (mass, COM, inertia).
    """
    m_bar = p.density * p.l2 * p.bar_width * p.bar_thickness
    w2, t2, l2 = p.bar_width**2, p.bar_thickness**2, p.l2**2
    bar = (m_bar, np.array([p.l2 / 2.0, 0.0, 0.0]), m_bar / 12.0 * np.diag([t2 + w2, l2 + w2, l2 + t2]))
    m_plate = p.density * p.plate_thickness * p.l3 * p.l1 / 2.0
    i_load = p.payload_mass * p.payload_size**2 / 6.0
    uu, vv, ww = p.l1**2 / 18.0, p.l3**2 / 24.0, p.plate_thickness**2 / 12.0
    plate = np.diag([m_plate * (uu + ww), m_plate * (vv + ww), m_plate * (vv + uu)]) + i_load * np.eye(3)
    out = {name: bar for name in BODIES[:-1]}
    out["platform"] = (m_plate + p.payload_mass, np.array([0.0, -2.0 * p.l1 / 3.0, 0.0]), plate)
    return out


def actuated(p: Parallel2T1RParams) -> tuple[str, ...]:
    """Actuated joints: R11, R21, R31, and R41 in the redundantly actuated variant.

    Args:
        p: the parameters.

    Returns:
        Joint names.
    """
    return ("R11", "R21", "R31", "R41") if p.redundant_actuation else ("R11", "R21", "R31")
