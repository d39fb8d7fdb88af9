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
from typing import TYPE_CHECKING

import numpy as np

from mechkit.exceptions import InvalidParameters
from mechkit.mechanisms.rocket_gimbal_kinematics import GimbalGeometry
from mechkit.mechanisms.rocket_gimbal_motion import GimbalMotion, gimbal_motion
from mechkit.mechanisms.rocket_gimbal_soc import BodySpec, gimbal_skcs
from mechkit.params import MechanismParams, param
from mechkit.contract import MechanismSpec
from mechkit.spatial import rot_x

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

#: Rotation from the paper frame O-xyz to the world frame (nozzle down, world z up).
PAPER_TO_WORLD = rot_x(np.pi)
#: The paper's linear rule: stroke 110 mm <-> 6.5 deg.
RULE_STROKE, RULE_ANGLE = 0.110, np.radians(6.5)
#: The paper's worked example: strokes (m), its FK answer (rad), its IK lengths of that answer (m).
PAPER_EXAMPLE = {
    "strokes": np.array([-0.060, 0.105]),
    "angles": np.radians([6.6336, -2.0624]),
    "lengths": np.array([1.7828855, 1.9479909]),
}


@dataclass(frozen=True)
class RocketGimbalParams(MechanismParams):
    pivot_radius: float = param(
        1.009116,
        "m",
        "r: distance of the actuator lines from the nozzle axis "
        "(reconstruction reproducing the paper's IK example)",
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
    engine_mass: float = param(
        2000.0, "kg", "YF-100 class kerosene/LOX engine (about 1.2 MN, ~2 t)", ours=True
    )
    engine_com: float = param(1.2, "m", "engine COM on the nozzle axis, from O", ours=True)
    engine_length: float = param(
        3.0, "m", "engine envelope length (uniform solid cylinder inertia)", ours=True
    )
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
    """The pivots of the paper frame O-xyz from the parameters."""
    return GimbalGeometry.reconstruction(p.pivot_radius, p.pivot_offset, p.length_a, p.length_b)


def _hinges(mech: Mechanism, x: np.ndarray, index: str = "v") -> np.ndarray:
    """(alpha, beta) entries of a joint vector (q with index="q", v or a with "v")."""
    pick = mech.q_index if index == "q" else mech.v_index
    return np.array([x[pick("bracket_hinge")], x[pick("engine_hinge")]])


def _bench_fk(method: str):
    """`mechkit bench` assembly by the paper's FK: (alpha, beta) by the resultant or Newton, then the
    servos' Hooke angles and strokes in closed form."""

    def assemble(mech: Mechanism, sample) -> np.ndarray:
        from mechkit.mechanisms.rocket_gimbal_kinematics import fk_newton
        from mechkit.mechanisms.rocket_gimbal_resultant import fk_resultant, pick_in_range

        geo, stroke = geometry(mech.params), np.asarray(sample.inputs, dtype=float)
        if method == "resultant":
            mode = pick_in_range(fk_resultant(geo, stroke))
            angles = np.array([mode.alpha, mode.beta])
        else:
            angles = fk_newton(geo, stroke)
        return joint_state(mech, gimbal_motion(geo, angles, np.zeros(2), np.zeros(2)))[0]

    return assemble


def _bench_soc(mech: Mechanism, sample):
    """SOC virtual work (numpy) with the analytic motion of (alpha, beta); no thrust (as the bench)."""
    from mechkit.validation.soc import solve_soc

    motion = gimbal_motion(
        geometry(mech.params), _hinges(mech, sample.q, "q"), _hinges(mech, sample.v), _hinges(mech, sample.a)
    )
    return solve_soc(soc_skcs(mech.params, motion, SwingScene(thrust=0.0)))


#: `mechkit bench` methods (protocol in `mechkit.bench`); the SOC is also the independent reference.
BENCH_METHODS = {
    "assembly": [
        ("paper FK: resultant + closed-form servos", _bench_fk("resultant")),
        ("Newton FK on the lengths + closed-form servos", _bench_fk("newton")),
    ],
    "inverse_dynamics": [("SOC (numpy)", _bench_soc)],
}
BENCH_REFERENCE = {"inverse_dynamics": _bench_soc}


def _swing_scene(mech: Mechanism) -> list[np.ndarray]:
    """One period of the swing scene as assembled configurations (for animated snapshots)."""
    scene = SwingScene()
    return [
        joint_state(mech, scene.motion(mech.params, t))[0]
        for t in np.linspace(0.0, 1.0 / scene.frequency, 120)
    ]


#: Animated scenes for `mechkit snapshot rocket_gimbal --scene swing`.
SCENES = {"swing": _swing_scene}


def _self_checks(mech: Mechanism) -> dict[str, float]:
    from mechkit.mechanisms.rocket_gimbal_checks import self_checks

    return self_checks(mech)


SPEC = MechanismSpec(
    name="rocket_gimbal",
    params=RocketGimbalParams,
    template="rocket_gimbal.urdf.xacro",
    actuated=("a_stroke", "b_stroke"),
    gruebler_dof=2,
    home=lambda p: {"a_stroke": 0.0, "b_stroke": 0.0},
    summary="launcher engine gimbal: frame-bracket-engine hinges at 45 deg, two U-P-S servo actuators",
    self_checks=_self_checks,
)


def body_inertias(p: RocketGimbalParams) -> BodySpec:
    """Mass (kg) and transverse / axial moments of inertia about the COM (kg m^2) of each moving body.

    Every body is axisymmetric: the engine and the servo parts are uniform solid cylinders about their
    axes, the bracket a thin ring about its normal, the Hooke crosses isotropic. The xacro computes the
    same from the same numbers.
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


@dataclass(frozen=True)
class SwingScene:
    """A conical swing manoeuvre in flight: alpha = A sin(w t), beta = B sin(w t + phase), under thrust.

    All values are ours: a YF-100-class sea-level thrust and a swing of a few degrees at 1 Hz
    (about 25 deg/s, the order of a launcher's thrust-vector slew rate).
    """

    amplitude_alpha: float = np.radians(4.0)  # rad
    amplitude_beta: float = np.radians(4.0)  # rad
    frequency: float = 1.0  # Hz
    phase: float = np.pi / 2  # rad
    thrust: float = 1.2e6  # N, against the nozzle axis
    thrust_point: float = 1.5  # m from O along the nozzle axis (the throat)

    def __post_init__(self) -> None:
        for name, value in vars(self).items():
            if not np.isfinite(value):
                raise InvalidParameters(name, value, "must be finite")
        if self.frequency <= 0 or self.thrust < 0:
            raise InvalidParameters(
                "frequency/thrust", (self.frequency, self.thrust), "need frequency > 0, thrust >= 0"
            )

    def angles(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(alpha, beta) rad, their rates rad/s and accelerations rad/s^2 at time t (s)."""
        w = 2.0 * np.pi * self.frequency
        amp = np.array([self.amplitude_alpha, self.amplitude_beta])
        arg = w * t + np.array([0.0, self.phase])
        return amp * np.sin(arg), amp * w * np.cos(arg), -amp * w**2 * np.sin(arg)

    def motion(self, p: RocketGimbalParams, t: float) -> GimbalMotion:
        """The analytic motion of every body at time t."""
        return gimbal_motion(geometry(p), *self.angles(t))


def joint_state(mech: Mechanism, motion: GimbalMotion) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(q, v, a) of the URDF tree from the analytic motion (no closure solve)."""
    p = mech.params
    values = {
        "bracket_hinge": (motion.angles[0], motion.rates[0], motion.accs[0]),
        "engine_hinge": (motion.angles[1], motion.rates[1], motion.accs[1]),
    }
    for name, leg, l0 in zip("ab", motion.legs, (p.length_a, p.length_b)):
        for i in range(2):
            values[f"{name}_swing_{i + 1}"] = (leg.hooke[i], leg.hooke_rate[i], leg.hooke_acc[i])
        values[f"{name}_stroke"] = (leg.length - l0, leg.length_rate, leg.length_acc)
    q, v, a = mech.neutral(), np.zeros(mech.model.nv), np.zeros(mech.model.nv)
    for joint, (x, xd, xdd) in values.items():
        q[mech.q_index(joint)], v[mech.v_index(joint)], a[mech.v_index(joint)] = x, xd, xdd
    return q, v, a


def thrust_fext(mech: Mechanism, q: np.ndarray, scene: SwingScene) -> list:
    """Pinocchio external forces (per joint, local frames): the thrust on the engine at q."""
    import pinocchio as pin

    pin.forwardKinematics(mech.model, mech.data, q)
    engine = mech.model.getJointId("engine_hinge")
    oMi = mech.data.oMi[engine]
    n = oMi.rotation[:, 2]  # the engine frame's z is the nozzle axis
    force = -scene.thrust * n
    point = oMi.translation + scene.thrust_point * n
    fext = [pin.Force.Zero() for _ in range(mech.model.njoints)]
    fext[engine] = oMi.actInv(pin.Force(force, np.cross(point, force)))
    return fext


def soc_skcs(p: RocketGimbalParams, motion: GimbalMotion, scene: SwingScene) -> list:
    """The SKCs of `rocket_gimbal_soc.gimbal_skcs` for these parameters (world frame)."""
    return gimbal_skcs(
        motion,
        geometry(p).frame_pivots,
        body_inertias(p),
        p.engine_com,
        p.cylinder_length,
        p.rod_length,
        PAPER_TO_WORLD,
        (scene.thrust, scene.thrust_point),
    )
