"""Two-way swinging mechanism of a launcher engine (Qian, Fu, Zhang, Zhu; reference 004).

The engine turns about a fixed point O: gimbal frame -> bracket about Ox1, bracket -> engine about
Oy2 (hinges at 45 deg to Ox / Oy, meeting at O). Two U-P-S actuators A and B drive it; their strokes
are the inputs. The paper's own analytic kinematics live in `rocket_gimbal_kinematics` (IK, Newton
FK, pitch / yaw, the linear rule) and `rocket_gimbal_resultant` (half-angle substitution, Sylvester
resultant, common-root test). Frames: the paper frame O-xyz (z along the nozzle) is the URDF link
`gimbal_frame`; it hangs nozzle-down from the world (`rocket`, z up): world = Rx(pi) * paper.

Not in the source (ours): the pivot coordinates (a reconstruction that reproduces the paper's
printed numbers), every mass and inertia, the actuator dimensions.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.exceptions import InvalidParameters
from mechkit.mechanisms.rocket_gimbal_kinematics import GimbalGeometry, rot_x
from mechkit.params import MechanismParams, param
from mechkit.registry import MechanismSpec

#: Rotation from the paper frame O-xyz to the world frame (nozzle down, world z up).
PAPER_TO_WORLD = rot_x(np.pi)
#: The paper's in-range limit on alpha and beta (rad).
SWING_LIMIT = np.radians(10.0)
#: The paper's linear rule: stroke 110 mm <-> 6.5 deg.
RULE_STROKE, RULE_ANGLE = 0.110, np.radians(6.5)


@dataclass(frozen=True)
class RocketGimbalParams(MechanismParams):
    pivot_radius: float = param(1.009116, "m", "r: distance of the actuator lines from the nozzle axis "
                                "(reconstruction reproducing the paper's IK example)", ours=True)
    pivot_offset: float = param(0.69511, "m", "h: engine pivots' height along the nozzle axis above O "
                                "(reconstruction)", ours=True)
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

    def validate(self) -> None:
        shortest = min(self.length_a, self.length_b) - RULE_STROKE
        if self.rod_length >= shortest or self.cylinder_length >= shortest:
            raise InvalidParameters("rod_length/cylinder_length", (self.rod_length, self.cylinder_length),
                                    f"each must be shorter than the shortest actuator length {shortest:.3f} m")
        if self.cylinder_length + self.rod_length <= max(self.length_a, self.length_b) + RULE_STROKE:
            raise InvalidParameters("rod_length/cylinder_length", (self.rod_length, self.cylinder_length),
                                    "rod and cylinder must overlap at full stroke")
        if abs(self.pivot_offset - self.length_a) < 1e-6 or abs(self.pivot_offset - self.length_b) < 1e-6:
            raise InvalidParameters("pivot_offset", self.pivot_offset,
                                    "frame pivots coplanar with O: the paper's mechanism has them off the plane")


def geometry(p: RocketGimbalParams) -> GimbalGeometry:
    """The pivots of the paper frame O-xyz from the parameters."""
    return GimbalGeometry.reconstruction(p.pivot_radius, p.pivot_offset, p.length_a, p.length_b)


SPEC = MechanismSpec(
    name="rocket_gimbal",
    params=RocketGimbalParams,
    xacro="rocket_gimbal.urdf.xacro",
    actuated=("a_stroke", "b_stroke"),
    gruebler_dof=2,
    home=lambda p: {"a_stroke": 0.0, "b_stroke": 0.0},
    summary="launcher engine gimbal: frame-bracket-engine hinges at 45 deg, two U-P-S servo actuators",
)
