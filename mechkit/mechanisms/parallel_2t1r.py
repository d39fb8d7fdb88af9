"""Spatial 2T1R parallel mechanism with a redundant limb (Huang, Shen, Li, Zhu, Yang; reference 001).

Parameters, registry entry, the paper's scenes (example inputs, motion law) and the bridge from the
paper's analytic kinematics (`parallel_2t1r_kinematics`) to the URDF's joint coordinates. The
URDF tree: base -> R_d1 -> link_d1 -> R_d2 -> link_d2 for the four limbs, platform on R23 at the tip
of link22; cuts R13 (link12/link22 at C1), R33 (link32/platform at C3), R43 (link42/platform at C4).

Actuation: R11, R21, R31 (theta_1..theta_3). With ``redundant_actuation=True`` R41 (theta_4) is
driven too: four motors for three degrees of freedom; the efforts are then fixed only up to the
mechanism's null space, and mechkit's validators use the minimum-norm distribution (see
`parallel_2t1r_soc.classic_torques`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.exceptions import InvalidParameters
from mechkit.mechanisms import parallel_2t1r_kinematics as kin
from mechkit.params import MechanismParams, param
from mechkit.registry import MechanismSpec

#: The assembled branch: index into `forward_kinematics` (C1 below the chord B1B2, first alpha
#: root) and into `follower_angles` (theta_4 = 0 at the motion law's start). Tables 1-2 of the paper
#: are lost; this is the branch that carries the whole motion law with limb III reachable and
#: starts with every limb at theta_d = 0 (the other FK branch that does, index 1, is its mirror).
ASSEMBLED = (2, 0)
#: The paper's example inputs theta_1..theta_3 (rad): 10, 20, 30 deg.
EXAMPLE_INPUTS = np.radians([10.0, 20.0, 30.0])
#: Motion law rates (rad/s): theta_1 = pi t/18, theta_2 = pi t/15, theta_3 = pi t/10, t in [0, 5] s.
MOTION_RATES = np.array([np.pi / 18.0, np.pi / 15.0, np.pi / 10.0])
MOTION_DURATION = 5.0
TREE_JOINTS = ("R11", "R12", "R21", "R22", "R23", "R31", "R32", "R41", "R42")


@dataclass(frozen=True)
class Parallel2T1RParams(MechanismParams):
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
        if self.l3 / 2.0 >= self.l1 + self.l2:
            raise InvalidParameters("l3", self.l3, "platform wider than the limbs can hold")
        if self.l2 <= self.bar_width:
            raise InvalidParameters("bar_width", self.bar_width, "must be smaller than the link length l2")

    @property
    def dims(self) -> kin.Dims:
        return kin.Dims(self.l1, self.l2, self.l3)


def mass_properties(p: Parallel2T1RParams) -> dict[str, tuple[float, np.ndarray, np.ndarray]]:
    """Mass (kg), COM (3,) m and inertia (3, 3) kg m^2 about the COM, in each body's own frame.

    Bars: local x along the link from its joint, box inertia; platform: frame at C1, x = u, y = v,
    triangular plate (height l1 between the limb planes) plus the payload cube at the centroid.
    The same numbers as the xacro template (a test compares them with the URDF).
    """
    m_bar = p.density * p.l2 * p.bar_width * p.bar_thickness
    w2, t2, l2 = p.bar_width**2, p.bar_thickness**2, p.l2**2
    bar = (m_bar, np.array([p.l2 / 2.0, 0.0, 0.0]), m_bar / 12.0 * np.diag([t2 + w2, l2 + w2, l2 + t2]))
    m_plate = p.density * p.plate_thickness * p.l3 * p.l1 / 2.0
    i_load = p.payload_mass * p.payload_size**2 / 6.0
    uu, vv, ww = p.l1**2 / 18.0, p.l3**2 / 24.0, p.plate_thickness**2 / 12.0
    plate = np.diag([m_plate * (uu + ww), m_plate * (vv + ww), m_plate * (vv + uu)]) + i_load * np.eye(3)
    out = {name: bar for name in kin.BODIES[:-1]}
    out["platform"] = (m_plate + p.payload_mass, np.array([0.0, -2.0 * p.l1 / 3.0, 0.0]), plate)
    return out


def actuated(p: Parallel2T1RParams) -> tuple[str, ...]:
    """Actuated joints: R11, R21, R31, and R41 in the redundantly actuated variant."""
    return ("R11", "R21", "R31", "R41") if p.redundant_actuation else ("R11", "R21", "R31")


def motion_law(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Inputs theta_1..theta_3 (rad), rates (rad/s), accelerations (rad/s^2) of the paper's law at t (s)."""
    return MOTION_RATES * t, MOTION_RATES.copy(), np.zeros(3)


def assembled_pose(p: Parallel2T1RParams, theta: np.ndarray) -> tuple[kin.Pose, float, float]:
    """The assembled pose for inputs theta_1..theta_3: pose, theta_4, FK discriminant.

    The branch is the `ASSEMBLED` root index; the root labels of `solve_trig` and of the C1 circle
    intersection are continuous away from double roots, so a fixed index follows a continuous
    motion that stays clear of singular poses.

    Raises:
        InvalidParameters: the inputs cannot be assembled (a limb out of reach).
    """
    d = p.dims
    pose, disc = kin.forward_kinematics(d, theta)[ASSEMBLED[0]]
    roots, _ = kin.follower_angles(d, pose)
    return pose, roots[ASSEMBLED[1]], disc


def state_at(p: Parallel2T1RParams, theta, theta_dot, theta_ddot) -> kin.State:
    """Full motion state of the assembled branch for the inputs, their rates and accelerations.

    Raises:
        SingularConfiguration: J_p singular (e.g. the motion law's start, t = 0).
    """
    pose, theta4, _ = assembled_pose(p, theta)
    return kin.motion_state(p.dims, theta, theta_dot, theta_ddot, pose, theta4)


def motion_law_states(p: Parallel2T1RParams, times: np.ndarray) -> list[kin.State]:
    """States along the motion law at ``times`` (s)."""
    return [state_at(p, *motion_law(float(t))) for t in times]


def joint_coordinates(p: Parallel2T1RParams, s: kin.State) -> dict[str, tuple[float, float, float]]:
    """URDF tree joints -> (position rad, rate rad/s, acceleration rad/s^2) for an analytic state."""
    motion = kin.link_motion(p.dims, s)
    out = {}
    for joint, child, parent in (("R11", "link11", None), ("R12", "link12", "link11"), ("R21", "link21", None),
                                 ("R22", "link22", "link21"), ("R23", "platform", "link22"),
                                 ("R31", "link31", None), ("R32", "link32", "link31"),
                                 ("R41", "link41", None), ("R42", "link42", "link41")):
        c = motion[child]
        if parent is None:  # R_d1: the paper's theta_d (link frame pitched by pi)
            ref_angle, ref_w, ref_e = np.pi, 0.0, 0.0
        else:
            ref = motion[parent]
            ref_angle, ref_w, ref_e = ref.angle, ref.omega[1], ref.alpha[1]
        q = float(np.angle(np.exp(1j * (c.angle - ref_angle))))
        out[joint] = (q, float(c.omega[1] - ref_w), float(c.alpha[1] - ref_e))
    return out


def _guess(p: Parallel2T1RParams) -> dict[str, float]:
    theta = EXAMPLE_INPUTS
    pose, theta4, _ = assembled_pose(p, theta)
    state = kin.State(pose, np.zeros(3), np.zeros(3), np.append(theta, theta4), np.zeros(4), np.zeros(4))
    return {joint: value[0] for joint, value in joint_coordinates(p, state).items()}


def _home(p: Parallel2T1RParams) -> dict[str, float]:
    home = dict(zip(("R11", "R21", "R31"), EXAMPLE_INPUTS))
    if p.redundant_actuation:
        home["R41"] = _guess(p)["R41"]
    return home


#: Compared quantities: efforts (N m) and the in-plane (determinate) reaction forces (N), world.
QUANTITIES = ("M1", "M2", "M3", "R23_fx", "R23_fz", "R43_fx", "R43_fz")
_EFFORT_JOINT = {"M1": "R11", "M2": "R21", "M3": "R31"}


def _row(efforts: dict[str, float], reactions: dict[str, np.ndarray]) -> np.ndarray:
    """Values of `QUANTITIES` from efforts by joint and reaction wrenches (6,) by joint."""
    return np.array([efforts[_EFFORT_JOINT[q]] if q in _EFFORT_JOINT
                     else reactions[q[:3]][0 if q.endswith("fx") else 2] for q in QUANTITIES])


def pinocchio_inverse_dynamics(mech, q: np.ndarray, v: np.ndarray, a: np.ndarray, m4: float | None = None):
    """`Mechanism.inverse_dynamics` of a non-redundant model, with R41's motor torque m4 (N m) as a
    known external torque on link41 when given (the redundant variant with a chosen distribution)."""
    import pinocchio as pin

    fext = None
    if m4 is not None:
        fext = [pin.Force.Zero() for _ in range(mech.model.njoints)]
        fext[mech.model.getJointId("R41")] = pin.Force(np.zeros(3), np.array([0.0, m4, 0.0]))
    return mech.inverse_dynamics(q, v, a, fext=fext)


@dataclass(frozen=True)
class Comparison:
    """Along a motion: `QUANTITIES` by the three methods, (n, 7) arrays (classic: efforts only, NaN
    columns for the reactions it does not give), and the Pinocchio-vs-analytic joint error (n,) rad."""

    times: np.ndarray
    pinocchio: np.ndarray
    soc: np.ndarray
    classic: np.ndarray
    kinematics_error: np.ndarray
    determinate: dict[str, np.ndarray]
    m4: np.ndarray | None = None

    def relative_error(self, other: str) -> np.ndarray:
        """Max |method - Pinocchio| / max |Pinocchio| per quantity (7,) (NaN where not given)."""
        values = getattr(self, other)
        scale = np.max(np.abs(self.pinocchio), axis=0)
        return np.max(np.abs(values - self.pinocchio), axis=0) / scale


def compare_along(mech, times: np.ndarray, redundant: bool = False) -> Comparison:
    """Pinocchio (closure solve + constrained RNEA), SOC and classic virtual work along the motion law.

    Pinocchio's motion is its own: `assemble` from a Taylor step of its previous sample (the first
    from the analytic state), `velocities`, `accelerations`; the analytic state only seeds the
    first guess and is compared joint by joint. ``redundant``: R41 driven too, torques distributed by minimum norm
    (`classic_torques`), the same m4 given to SOC and to Pinocchio.

    Raises:
        SingularConfiguration: a sample is singular for one of the methods (e.g. t = 0).
    """
    from mechkit.mechanisms.parallel_2t1r_soc import classic_torques, soc_inverse_dynamics

    p = mech.params
    states = motion_law_states(p, times)
    pin_rows, soc_rows, cls_rows, kin_err, m4s = [], [], [], [], []
    q = v = a = None
    flags: dict[str, np.ndarray] = {}
    previous = None
    for t, s in zip(times, states):
        coords = joint_coordinates(p, s)
        if q is None:
            guess = {j: c[0] for j, c in coords.items()}
        else:  # Taylor predictor from Pinocchio's own previous sample
            dt = float(t - previous)
            guess = q + v * dt + 0.5 * a * dt * dt
        previous = t
        theta, rates, acc = motion_law(float(t))
        q = mech.assemble(dict(zip(("R11", "R21", "R31"), theta)), guess=guess)
        v = mech.velocities(q, rates, inputs=("R11", "R21", "R31"))
        a = mech.accelerations(q, v, acc, inputs=("R11", "R21", "R31"))
        kin_err.append(max(abs(np.angle(np.exp(1j * (q[mech.q_index(j)] - c[0])))) for j, c in coords.items()))
        actuators = ("R11", "R21", "R31", "R41") if redundant else ("R11", "R21", "R31")
        efforts, _ = classic_torques(p, s, actuators)
        m4 = efforts.get("R41")
        m4s.append(m4)
        result = pinocchio_inverse_dynamics(mech, q, v, a, m4)
        if not flags:
            flags = {j: result.reactions[j].determinate for j in ("R23", "R43")}
        pin_rows.append(_row(result.efforts, {j: r.wrench for j, r in result.reactions.items()}))
        soc = soc_inverse_dynamics(p, s, m4)
        soc_rows.append(_row(soc.efforts, soc.reactions))
        cls_rows.append([efforts[_EFFORT_JOINT[k]] if k in _EFFORT_JOINT else np.nan for k in QUANTITIES])
    return Comparison(np.asarray(times), np.array(pin_rows), np.array(soc_rows), np.array(cls_rows),
                      np.array(kin_err), flags, np.array(m4s) if redundant else None)


def self_checks(mech) -> dict[str, float]:
    """`mechkit report` rows: FK/IK of the paper's example and SOC / classic vs Pinocchio (26 samples)."""
    d = mech.params.dims
    worst_residual, worst_trip = 0.0, 0.0
    for pose, _ in kin.forward_kinematics(d, EXAMPLE_INPUTS):
        for sol in kin.inverse_kinematics(d, pose):
            worst_residual = max(worst_residual, np.max(np.abs(kin.loop_residuals(d, np.append(sol, 0.0), pose)[:3])))
        trip = np.min(np.abs(np.angle(np.exp(1j * (kin.inverse_kinematics(d, pose) - EXAMPLE_INPUTS)))).max(axis=1))
        worst_trip = max(worst_trip, float(trip))
    cmp = compare_along(mech, np.linspace(0.2, MOTION_DURATION, 25))
    rel = lambda m: float(np.nanmax(cmp.relative_error(m)))  # noqa: E731
    return {"analytic IK closure residual, paper example (m)": worst_residual,
            "FK -> IK round trip, paper example (rad)": worst_trip,
            "analytic vs Pinocchio joint angles, motion law (rad)": float(cmp.kinematics_error.max()),
            "SOC vs Pinocchio, torques + in-plane R23/R43 (rel.)": rel("soc"),
            "classic virtual work vs Pinocchio, torques (rel.)": rel("classic")}


SPEC = MechanismSpec(
    name="parallel_2t1r",
    params=Parallel2T1RParams,
    xacro="parallel_2t1r.urdf.xacro",
    actuated=actuated,
    gruebler_dof=3,
    home=_home,
    guess=_guess,
    summary="spatial 2T1R parallel mechanism, five-bar limb + 2 RRR limbs, all axes along y (ref. 001)",
    self_checks=self_checks,
)
