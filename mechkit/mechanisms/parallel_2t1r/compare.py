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

from mechkit.exceptions import InvalidParameters, MechkitError, SingularConfiguration
from mechkit.mechanisms import parallel_2t1r_kinematics as kin
from mechkit.params import MechanismParams, param
from mechkit.contract import MechanismSpec

#: The assembled branch: (C1 root, alpha root) of `forward_kinematics` (C1 below the chord B1B2,
#: first alpha root) and the root of `follower_angles` (theta_4 = 0 at the motion law's start).
#: Tables 1-2 of the paper are lost; this branch carries the whole motion law with limb III
#: reachable and starts with every limb at theta_d = 0 (so does its mirror, branch (0, 1)).
ASSEMBLED = ((1, 0), 0)
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
        try:  # the home assembly: the paper's example inputs on the assembled branch
            assembled_pose(self, EXAMPLE_INPUTS)
        except InvalidParameters as err:
            why = f"the example inputs (10, 20, 30 deg) do not assemble: {err.why}"
            raise InvalidParameters("l1, l2, l3", (self.l1, self.l2, self.l3), why) from None

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
    found = [s for s in kin.forward_kinematics(d, theta) if s.branch == ASSEMBLED[0]]
    if not found:
        raise InvalidParameters("theta", theta, f"no pose on the assembled branch {ASSEMBLED[0]}")
    roots, _ = kin.follower_angles(d, found[0].pose)
    return found[0].pose, roots[ASSEMBLED[1]], found[0].discriminant


def state_at(p: Parallel2T1RParams, theta, theta_dot, theta_ddot) -> kin.State:
    """Full motion state of the assembled branch for the inputs, their rates and accelerations.

    Raises:
        SingularConfiguration: J_p singular (e.g. the motion law's start, t = 0).
    """
    pose, theta4, _ = assembled_pose(p, theta)
    return kin.motion_state(p.dims, theta, theta_dot, theta_ddot, pose, theta4)


def at_rest(pose: kin.Pose, theta: np.ndarray, theta4: float) -> kin.State:
    """The state of a configuration at rest (every rate and acceleration zero)."""
    return kin.State(pose, np.zeros(3), np.zeros(3), np.append(theta, theta4), np.zeros(4), np.zeros(4))


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


def joint_positions(p: Parallel2T1RParams, s: kin.State) -> dict[str, float]:
    """URDF tree joints -> position (rad) of an analytic state: a closure-solve guess."""
    return {joint: c[0] for joint, c in joint_coordinates(p, s).items()}


def _guess(p: Parallel2T1RParams) -> dict[str, float]:
    pose, theta4, _ = assembled_pose(p, EXAMPLE_INPUTS)
    return joint_positions(p, at_rest(pose, EXAMPLE_INPUTS, theta4))


def _home(p: Parallel2T1RParams) -> dict[str, float]:
    home = dict(zip(("R11", "R21", "R31"), EXAMPLE_INPUTS))
    if p.redundant_actuation:
        home["R41"] = _guess(p)["R41"]
    return home


INPUTS = ("R11", "R21", "R31")
#: Compared quantities: efforts (N m) and the in-plane (determinate) reaction forces (N), world.
QUANTITIES = ("M1", "M2", "M3", "R23_fx", "R23_fz", "R43_fx", "R43_fz")
_EFFORT_JOINT = {"M1": "R11", "M2": "R21", "M3": "R31", "M4": "R41"}
METHODS = ("pinocchio", "soc", "classic")


def pinocchio_motion(mech, theta: np.ndarray, rates: np.ndarray, acc: np.ndarray, guess) -> tuple[np.ndarray, ...]:
    """Pinocchio's own motion for the inputs: closure solve from ``guess``, then v and a (SI).

    Raises:
        ClosureNotConverged, SingularConfiguration: from `Mechanism.assemble` / `velocities`.
    """
    q = mech.assemble(dict(zip(INPUTS, theta)), guess=guess)
    v = mech.velocities(q, rates, inputs=INPUTS)
    return q, v, mech.accelerations(q, v, acc, inputs=INPUTS)


def pinocchio_inverse_dynamics(mech, q: np.ndarray, v: np.ndarray, a: np.ndarray, m4: float | None = None,
                               determinacy: bool = True):
    """`Mechanism.inverse_dynamics` of a non-redundant model, with R41's motor torque m4 (N m) as a
    known external torque on link41 when given (the redundant variant with a chosen distribution)."""
    import pinocchio as pin

    fext = None
    if m4 is not None:
        fext = [pin.Force.Zero() for _ in range(mech.model.njoints)]
        fext[mech.model.getJointId("R41")] = pin.Force(np.zeros(3), np.array([0.0, m4, 0.0]))
    return mech.inverse_dynamics(q, v, a, fext=fext, determinacy=determinacy)


def evaluate(mech, s: kin.State, motion: tuple[np.ndarray, ...] | None, redundant: bool = False,
             determinacy: bool = False) -> tuple[dict[str, float], dict[str, str], dict[str, np.ndarray]]:
    """Every method at one instant: values named "<method>:<quantity>", failures by method, and the
    determinacy flags (6,) of Pinocchio's R13, R23, R43 reactions (empty without ``determinacy``).

    Quantities: M1..M3 (M4 when ``redundant``, minimum-norm by classic virtual work and handed to
    the others), R23/R43 fx, fz (SOC, Pinocchio), R13 fx, fz (Pinocchio: the five-bar's compound
    hinge, inside SKC1 for SOC) and each method's condition number ("<method>:cond"). A method that
    raises a `MechkitError` (e.g. `SingularConfiguration`) gives no values and its message.

    Args:
        s: the analytic state (for SOC and classic virtual work).
        motion: Pinocchio's (q, v, a), or None to skip Pinocchio.
        determinacy: run the core's determinacy rank test (and get Pinocchio's condition number).
    """
    from mechkit.mechanisms.parallel_2t1r_soc import classic_torques, soc_inverse_dynamics

    p = mech.params
    out: dict[str, float] = {}
    failed: dict[str, str] = {}
    flags: dict[str, np.ndarray] = {}
    m4 = None
    try:
        efforts, cond = classic_torques(p, s, INPUTS + (("R41",) if redundant else ()))
        out |= {f"classic:{k}": efforts[j] for k, j in _EFFORT_JOINT.items() if j in efforts}
        out["classic:cond"] = cond
        m4 = efforts.get("R41")
    except MechkitError as err:
        failed["classic"] = str(err)
    runs = [("soc", lambda: soc_inverse_dynamics(p, s, m4))]
    if motion is not None:
        runs.append(("pinocchio", lambda: pinocchio_inverse_dynamics(mech, *motion, m4, determinacy)))
    for method, run in runs:
        if redundant and m4 is None:
            failed[method] = "no R41 torque: the minimum-norm distribution failed"
            continue
        try:
            result = run()
        except MechkitError as err:
            failed[method] = str(err)
            continue
        wrenches = {j: getattr(w, "wrench", w) for j, w in result.reactions.items()}
        out |= {f"{method}:{k}": result.efforts[j] for k, j in _EFFORT_JOINT.items() if j in result.efforts}
        for joint in ("R13", "R23", "R43"):
            if joint in wrenches:
                out[f"{method}:{joint}_fx"], out[f"{method}:{joint}_fz"] = wrenches[joint][[0, 2]]
        if method == "soc":
            out["soc:cond"] = max(result.condition.values())
        else:
            out["pinocchio:cond"] = result.condition
            if determinacy:
                flags = {j: result.reactions[j].determinate for j in ("R13", "R23", "R43")}
                out |= {f"pinocchio:{j}_inplane_determinate": float(f[0] and f[2]) for j, f in flags.items()}
    return out, failed, flags


@dataclass(frozen=True)
class Comparison:
    """`QUANTITIES` (n, 7) by each method along a motion (classic: NaN for the reactions it does not
    give), the Pinocchio-vs-analytic joint error (n,) rad, and the determinacy flags (6,) of the
    Pinocchio reactions at R23 and R43 (first sample)."""

    times: np.ndarray
    values: dict[str, np.ndarray]
    kinematics_error: np.ndarray
    determinate: dict[str, np.ndarray]

    def relative_error(self, method: str) -> np.ndarray:
        """Max |method - Pinocchio| / max |Pinocchio| per quantity (7,) (NaN where not given)."""
        ref = self.values["pinocchio"]
        return np.max(np.abs(self.values[method] - ref), axis=0) / np.max(np.abs(ref), axis=0)


def compare_along(mech, times: np.ndarray, redundant: bool = False) -> Comparison:
    """Pinocchio (closure solve + constrained RNEA), SOC and classic virtual work along the motion law.

    Pinocchio's motion is its own: `assemble` from a Taylor step of its previous sample (the first
    from the analytic state), `velocities`, `accelerations`; the analytic state seeds only the first
    guess and is compared joint by joint. ``redundant``: R41 driven too, torques distributed by
    minimum norm (`classic_torques`), the same M4 handed to SOC and Pinocchio.

    Raises:
        SingularConfiguration: a sample is singular for one of the methods (e.g. t = 0).
    """
    p = mech.params
    rows: dict[str, list] = {m: [] for m in METHODS}
    kin_err = []
    q = v = a = None
    flags: dict[str, np.ndarray] = {}
    previous = 0.0
    for t in np.asarray(times, dtype=float):
        theta, rates, acc = motion_law(t)
        s = state_at(p, theta, rates, acc)
        coords = joint_coordinates(p, s)
        dt = t - previous
        guess = joint_positions(p, s) if q is None else q + v * dt + 0.5 * a * dt * dt
        previous = t
        q, v, a = pinocchio_motion(mech, theta, rates, acc, guess)
        kin_err.append(max(abs(np.angle(np.exp(1j * (q[mech.q_index(j)] - c[0])))) for j, c in coords.items()))
        values, failed, determinate = evaluate(mech, s, (q, v, a), redundant, determinacy=not flags)
        if failed:
            method, why = next(iter(failed.items()))
            raise SingularConfiguration(np.inf, f"t = {t} s, {method}: {why}")
        flags = flags or determinate
        for m in METHODS:
            rows[m].append([values.get(f"{m}:{k}", np.nan) for k in QUANTITIES])
    return Comparison(np.asarray(times, dtype=float), {m: np.array(r) for m, r in rows.items()},
                      np.array(kin_err), flags)


#: Singular-approach study: theta_2, theta_3 held at the example's 20 and 30 deg while theta_1 is
#: driven up to theta_2: at theta_1 = theta_2 the chord B1B2 equals A1A2 = l1 = 2 l2, the
#: five-bar's distal links are collinear (C1 a double root of eq. (7)).
SINGULAR_HELD = EXAMPLE_INPUTS[1:]


@dataclass(frozen=True)
class Study:
    """Series along an approach parameter x (n,): values by series name (n,), NaN where the method
    raised, and the failures by series name: (x, error message) of every sample where it raised."""

    x: np.ndarray
    values: dict[str, np.ndarray]
    failures: dict[str, list[tuple[float, str]]]


def _study(x: np.ndarray, samples) -> Study:
    """Collect `evaluate`-style (values, failures) per sample into a `Study`."""
    collected: list[tuple[dict[str, float], dict[str, str]]] = list(samples)
    names = sorted({k for values, _ in collected for k in values})
    values = {k: np.array([v.get(k, np.nan) for v, _ in collected], dtype=float) for k in names}
    failures: dict[str, list[tuple[float, str]]] = {}
    for xi, (_, failed) in zip(x, collected):
        for method, why in failed.items():
            failures.setdefault(method, []).append((float(xi), why))
    return Study(np.asarray(x, dtype=float), values, failures)


def singular_approach(mech, deltas: np.ndarray) -> Study:
    """At rest under gravity, theta_1 = theta_2 - delta (rad) with `SINGULAR_HELD`: both variants.

    Series: "<method>:<quantity>" as in `evaluate` for the paper's three motors, the same prefixed
    "redundant/" for R41 driven too (minimum-norm torques), and "cond_Jp" (analytic J_p). Pinocchio
    assembles from the analytic configuration and is evaluated at rest.
    """
    p = mech.params

    def sample(delta: float):
        theta = np.array([SINGULAR_HELD[0] - delta, *SINGULAR_HELD])
        pose, theta4, _ = assembled_pose(p, theta)
        s = at_rest(pose, theta, theta4)
        values, failed = {"cond_Jp": float(np.linalg.cond(kin.jacobians(p.dims, s.theta, pose)[0]))}, {}
        try:
            q = mech.assemble(dict(zip(INPUTS, theta)), guess=joint_positions(p, s))
            motion = (q, np.zeros(mech.model.nv), np.zeros(mech.model.nv))
        except MechkitError as err:
            motion, failed["pinocchio"] = None, str(err)
        for redundant, prefix in ((False, ""), (True, "redundant/")):
            v, f, _ = evaluate(mech, s, motion, redundant, determinacy=True)
            values |= {prefix + k: x for k, x in v.items()}
            failed |= {prefix + k: x for k, x in f.items()}
        return values, failed

    return _study(deltas, (sample(float(d)) for d in deltas))


def start_of_motion(mech, times: np.ndarray) -> Study:
    """The motion law near its singular start (t -> 0+): three motors, Pinocchio's own motion.

    Series as in `evaluate` plus "cond_Jp" and "analytic:x_ddot" (|platform acceleration| of eq.
    (15)); a sample whose analytic state or Pinocchio motion raises is recorded as a failure.
    """
    p = mech.params

    def sample(t: float):
        theta, rates, acc = motion_law(t)
        pose, theta4, disc = assembled_pose(p, theta)
        values = {"fk_discriminant": disc,
                  "cond_Jp": float(np.linalg.cond(kin.jacobians(p.dims, np.append(theta, theta4), pose)[0]))}
        failed = {}
        try:
            s = state_at(p, theta, rates, acc)
        except MechkitError as err:
            failed["analytic"] = str(err)
            s = at_rest(pose, theta, theta4)
        values["analytic:x_ddot"] = float(np.linalg.norm(s.x_ddot)) if "analytic" not in failed else np.nan
        try:
            motion = pinocchio_motion(mech, theta, rates, acc, joint_positions(p, s))
        except MechkitError as err:
            motion, failed["pinocchio"] = None, str(err)
        v, f, _ = evaluate(mech, s, motion, determinacy=True)
        if "analytic" in failed:  # SOC and classic ran on the state at rest: not the motion's values
            v = {k: x for k, x in v.items() if k.startswith("pinocchio")}
            f |= {m: "no analytic motion state" for m in ("soc", "classic") if m not in f}
        return values | v, failed | f

    return _study(times, (sample(float(t)) for t in times))


def self_checks(mech) -> dict[str, float]:
    """`mechkit report` rows: FK/IK of the paper's example and SOC / classic vs Pinocchio (26 samples)."""
    d = mech.params.dims
    worst_residual, worst_trip = 0.0, 0.0
    for pose in (s.pose for s in kin.forward_kinematics(d, EXAMPLE_INPUTS)):
        for sol in kin.inverse_kinematics(d, pose):
            worst_residual = max(worst_residual, np.max(np.abs(kin.loop_residuals(d, np.append(sol, 0.0), pose)[:3])))
        trip = np.min(np.abs(np.angle(np.exp(1j * (kin.inverse_kinematics(d, pose) - EXAMPLE_INPUTS)))).max(axis=1))
        worst_trip = max(worst_trip, float(trip))
    cmp = compare_along(mech, np.linspace(0.2, MOTION_DURATION, 25))
    rel = lambda m: float(np.nanmax(cmp.relative_error(m)))
    return {"analytic IK closure residual, paper example (m)": worst_residual,
            "FK -> IK round trip, paper example (rad)": worst_trip,
            "analytic vs Pinocchio joint angles, motion law (rad)": float(cmp.kinematics_error.max()),
            "SOC vs Pinocchio, torques + in-plane R23/R43 (rel.)": rel("soc"),
            "classic virtual work vs Pinocchio, torques (rel.)": rel("classic")}


def _motion_law_scene(mech) -> list[np.ndarray]:
    """Configurations q along the paper's motion law, t = 0..5 s every 0.05 s (analytic positions)."""
    poses = []
    for t in np.linspace(0.0, MOTION_DURATION, 101):
        theta = motion_law(float(t))[0]
        pose, theta4, _ = assembled_pose(mech.params, theta)
        q = mech.neutral()
        for joint, value in joint_positions(mech.params, at_rest(pose, theta, theta4)).items():
            q[mech.q_index(joint)] = value
        poses.append(q)
    return poses


#: Animated scenes for `mechkit.viz` and the camera direction (the motion is in the x-z plane).
SCENES = {"motion_law": _motion_law_scene}
VIEW = (0.35, -1.0, 0.45)

SPEC = MechanismSpec(
    name="parallel_2t1r",
    params=Parallel2T1RParams,
    template="parallel_2t1r.urdf.xacro",
    actuated=actuated,
    gruebler_dof=3,
    home=_home,
    guess=_guess,
    summary="spatial 2T1R parallel mechanism, five-bar limb + 2 RRR limbs, all axes along y (ref. 001)",
    self_checks=self_checks,
)


def example_configurations(mech) -> list[np.ndarray]:
    """Every assembly of the paper's example (theta = 10, 20, 30 deg): each forward pose limb III can
    reach, with each of its theta4 roots, closed by the core's solver from the analytic configuration."""
    out = []
    for sol in kin.forward_kinematics(mech.params.dims, EXAMPLE_INPUTS):
        try:
            roots, _ = kin.follower_angles(mech.params.dims, sol.pose)
        except InvalidParameters:
            continue  # limb III cannot reach this pose
        for theta4 in roots:
            q = mech.neutral()
            for joint, (value, _, _) in joint_coordinates(mech.params, at_rest(sol.pose, EXAMPLE_INPUTS, theta4)).items():
                q[mech.q_index(joint)] = value
            out.append(mech.assemble(EXAMPLE_INPUTS, guess=q))
    return out
