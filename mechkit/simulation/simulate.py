"""`simulate`: a mechanism moving under its own forces, its drives and its events, from t0 for a duration.

Each accepted step of the integrator (`integrator`) is followed by the projection onto the closures
and drives (`projection`); a step in which an event's function changes sign ends at the crossing,
where the event acts (`events`: an impact, a joint held or released). Every accepted step is a
sample; after the run, every sample's reactions come from the core's inverse dynamics (the drives as
actuators, the elements' loads as passive and external forces), which also checks the efforts the
dynamics found.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from mechkit import core
from mechkit.base.exceptions import InvalidParameters
from mechkit.forces import ForceElement
from mechkit.history.axes import JointAxes
from mechkit.history.result import MotionResult, coordinate_names
from mechkit.simulation.anchor_reactions import applies as anchors_apply
from mechkit.simulation.crossing import FALLBACK, BranchChanged, BranchMode, BranchWatch, on_manifold
from mechkit.simulation.declared import default_forces, file_limits, torque_motors
from mechkit.simulation.events import REST_RATE, Latch, Limit, impact
from mechkit.simulation.floating import default_dynamics, run_momentum
from mechkit.simulation.integrator import ATOL, RTOL, Event, IntegrationFailed, Options, Stepper, first_crossing
from mechkit.simulation.jacobian import SystemJacobian
from mechkit.simulation.prescribed import Drives, prescribed
from mechkit.simulation.projection import Projection
from mechkit.simulation.recorder import Recorder
from mechkit.simulation.result import SimulationResult
from mechkit.simulation.state_layout import StateLayout
from mechkit.simulation.system import MechanismSystem

Progress = Callable[[float, float], None]
"""(time simulated, duration) -> None, after every accepted step."""

#: Accepted steps allowed to one run (ours: a guard against a step size collapsing without failing).
MAX_STEPS = 2_000_000
#: Times a step that left its branch is taken again, each a quarter of the last (ours).
BRANCH_RETRIES = 6


def simulate(
    mech: Any,
    duration: float,
    *,
    inputs: Any = None,
    input_names: Sequence[str] | None = None,
    torques: Any = None,
    forces: Sequence[ForceElement] = (),
    file_forces: bool = True,
    source: str | Path | None = None,
    q0: np.ndarray | None = None,
    v0: np.ndarray | None = None,
    t0: float = 0.0,
    dt: float | None = None,
    rtol: float = RTOL,
    atol: float = ATOL,
    method: str = "RK45",
    max_step: float = math.inf,
    dynamics: str | None = None,
    baumgarte: tuple[float, float] | None = None,
    friction_scheme: str | None = None,
    project: bool = True,
    limits: str | Sequence[Limit] | None = "file",
    restitution: float = 0.0,
    latches: Sequence[Latch] = (),
    reactions: bool = True,
    progress: Progress | None = None,
) -> SimulationResult:
    """Simulate a mechanism for `duration` seconds.

    Args:
        mech: the mechanism (`mechkit.Mechanism`).
        duration: simulated time (s, > 0).
        inputs: prescribed joints (computed-torque motors, their efforts recorded): an input law
            (`mechkit.motion.InputLaw`), a function t -> (positions, rates, accelerations) with
            `input_names`, or a mapping joint -> value held still; None: no prescribed joint.
        input_names: the joints of a law given as a function.
        torques: given efforts on actuators (see `torque_motors`), or None.
        forces: force elements added to the description's (`mechkit.forces`).
        file_forces: include the description's own elements (`default_forces`).
        source: the description file where the mechanism came from an MJCF file (for its frictionloss,
            ranges and force ranges); else the mechanism's URDF is read.
        q0: (nq,) the initial configuration (default: the home assembly); projected onto the closures
            and the drives at t0.
        v0: (nv,) the initial velocities (default: at rest); projected likewise.
        t0: the initial time (s).
        dt: a fixed step (s); None: adaptive steps to `rtol`, `atol` (`mechkit.simulation.integrator`).
        rtol: the adaptive steps' relative tolerance (scipy's meaning).
        atol: their absolute tolerance (scipy's meaning).
        method: the one-step method ("RK45", "DOP853", "RK23", "Radau"; "RK4", "SymplecticEuler" and
            "ImplicitMidpoint" at a fixed step `dt` only: `mechkit.simulation.fixed_step`).
        max_step: the largest adaptive step (s).
        dynamics: the core's forward-dynamics method ("proximal", "lcaba", "kkt", "nullspace"); None:
            "proximal" (Pinocchio's constraint models; friction reads the reactions from its multipliers
            where they are the inverse dynamics' ones, `simulation.anchor_reactions.applies`, else "kkt"
            and the core's inverse dynamics), or "kkt" where Pinocchio's constraint models cannot express
            a cut or coupling (`core.pinocchio_methods_apply`).
        baumgarte: (Kp 1/s^2, Kd 1/s) closure stabilisation in the accelerations, or None.
        friction_scheme: friction from the reactions per evaluation, "corrected" or "fixed point"
            (`mechkit.simulation.system`); None: "corrected" at a fixed step, "fixed point" with adaptive
            steps (the corrected friction's error, about 1e-6 of the accelerations, is noise to an error
            control at rtol 1e-9: measured on the ten-bar's deployment, 3.3 times the steps).
        project: project onto the closures and drives after every step (off: the drift shows).
        limits: "file" (the description's joint limits), a list of `Limit`, or None.
        restitution: the restitution of the description's limits (0: stop and hold; 1: elastic).
        latches: joints that lock when they reach a value (`Latch`).
        reactions: compute every sample's reactions (the core's inverse dynamics).
        progress: called after each accepted step with (time simulated, duration).

    Returns:
        `SimulationResult` (every accepted step a sample; energy balance, closure residual, events).

    Raises:
        InvalidParameters: bad options, unknown joints.
        IntegrationFailed: the step size collapsed or the steps ran out.
        FrictionLocks: friction locks the mechanism.
        ClosureNotConverged: a projection found no closure.
    """
    if not (isinstance(duration, (int, float)) and duration > 0 and math.isfinite(duration)):
        raise InvalidParameters("duration", duration, "must be a positive number of seconds")
    Options(method, rtol, atol, dt, max_step, npos=0)  # the options checked before anything is built
    drives = prescribed(inputs, input_names)
    elements = (
        (default_forces(mech, source) if file_forces else []) + list(forces) + torque_motors(mech, torques, source)
    )
    names = [e.name for e in elements]
    if len(set(names)) != len(names):
        raise InvalidParameters("forces", names, "every force element needs its own name")
    exact = any(e.needs_reactions for e in elements) and not anchors_apply(mech.closure_model)
    exact = exact or not core.pinocchio_methods_apply(mech.closure_model)
    dynamics, note = default_dynamics(mech.model, exact) if dynamics is None else (dynamics, "")
    if friction_scheme is None:
        friction_scheme = "fixed point" if dt is None else "corrected"
    system = MechanismSystem(mech, elements, drives, dynamics, baumgarte, friction_scheme)
    layout = StateLayout(mech.model, 1 + len(elements))
    options = Options(method, rtol, atol, dt, max_step, npos=layout.npos)
    projection = Projection(mech)
    limit_list = file_limits(mech, source, restitution) if limits == "file" else list(limits or ())
    for j in [x.joint for x in limit_list] + [x.joint for x in latches]:
        mech.v_index(j)
    recorder = Recorder(system, layout, projection)
    cache: dict = {}
    stopped: set[str] = set()  # joints held because they stopped at a bound (released when pulled off it)

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        if recorder.cached(cache, t, y):  # the sample's own evaluation: a step's first stage where it starts
            ev, q, v = cache["ev"], layout.q(y), layout.v(y)
            return layout.derivative(y, ev.a, np.concatenate([[float(ev.efforts @ v[system.drive_v])], ev.powers]))
        q, v = layout.q(y), layout.v(y)
        if mode.near:  # crossing: the stages on the manifold (near a singular position, or redundant rows)
            q, v = on_manifold(projection, system.drives, t, q, v)
            y = layout.pack(q, v, layout.works(y))
        ev = system.evaluate(t, q, v)
        recorder.keep(cache, t, y, ev)
        recorder.evaluations += 1
        drive_power = float(ev.efforts @ v[system.drive_v])
        return layout.derivative(y, ev.a, np.concatenate([[drive_power], ev.powers]))

    t_end = t0 + duration
    q = mech.home_q.copy() if q0 is None else np.array(q0, dtype=float)
    v = np.zeros(mech.model.nv) if v0 is None else np.array(v0, dtype=float)
    if project:
        q = projection.positions(q, system.drives, t0)
        v = projection.velocities(q, v, system.drives, t0)
    t, y = t0, layout.pack(q, v, np.zeros(1 + len(elements)))
    # crossing: the rank watch, and the near-singular mode where the method asked fails (simulation.crossing)
    watch = BranchWatch(mech, q) if project and layout.euclidean else None
    jacobian = SystemJacobian(system, layout, lambda: mode.near).current if method == "Radau" else None
    stepper = Stepper(rhs, t_end, options, jacobian)
    mode = BranchMode(watch, system, dynamics, stepper)
    stepper.restart(t, y)
    recorder.record(t, y, cache)
    value = _joint_value(mech, layout)
    while t < t_end - 1e-12 * max(1.0, abs(t_end)):
        if recorder.steps >= MAX_STEPS:
            raise IntegrationFailed(t, f"{MAX_STEPS} steps taken")
        q = layout.q(y)
        mode.before(t, q, y, projection.singular_values(q) if watch is not None else None)
        for attempt in range(BRANCH_RETRIES + 1):
            try:
                t1, y1 = stepper.step()
            except FALLBACK as err:
                mode.fallback(err, t, layout.q(y), y)
                continue
            events = _events(system.drives, limit_list, latches, value)
            hit = first_crossing(events, stepper.dense(), t, y, t1, y1) if events else None
            if hit is not None:
                t1 = hit[1]
                y1 = stepper.dense()(t1)
            q1, v1 = layout.q(y1), layout.v(y1).copy()
            if not project:
                break
            q1 = projection.positions(q1, system.drives, t1)
            v1 = projection.velocities(q1, v1, system.drives, t1)
            try:
                if watch is not None and not system.drives.all:  # driven joints: their law sets the rates
                    watch.check(t1, layout.q(y), layout.q(y1), layout.v(y1), q1, v1, mode.searching)
                break
            except BranchChanged as err:
                mode.retry(err, attempt == BRANCH_RETRIES, t, t1, y)
        else:
            raise IntegrationFailed(t, f"the step failed {BRANCH_RETRIES + 1} times")
        if mode.searching and (crossing := watch.passed(stepper.dense(), t, t1, layout.q)) is not None:
            recorder.event(
                crossing.t,
                f"singular:{crossing.joint}",
                f"passed a singular position on its branch (mobility {crossing.mobility} there, "
                f"relative singular-value ratio {crossing.ratio:.3g})",
            )
        if hit is not None:
            v1 = _act(events[hit[0]].name, system, recorder, limit_list, latches, t1, q1, v1, stopped)
        _release(system, recorder, limit_list, t1, q1, v1, stopped)
        t, y = t1, layout.pack(q1, v1, layout.works(y1))
        if t < t_end - 1e-12 * max(1.0, abs(t_end)):
            try:
                stepper.restart(t, y)
            except FALLBACK as err:
                mode.fallback(err, t, q1, y)
        recorder.steps += 1
        recorder.record(t, y, cache)
        if progress is not None:
            progress(t - t0, duration)
    info = {
        "method": method if dt is None else f"{method}, fixed step {dt:g} s",
        "rtol": rtol,
        "atol": atol,
        "dt": dt,
        "dynamics": dynamics,
        "dynamics_note": note,
        "projection": project,
        "steps": recorder.steps,
        "evaluations": recorder.evaluations,
        "singular_crossings": len(watch.crossings) if watch is not None else 0,
        "redundant_rows": watch.redundant if watch is not None else 0,
    }
    return _result(mech, recorder, elements, info, inputs, reactions)


def _joint_value(mech: Any, layout: StateLayout) -> Callable[[str, np.ndarray], float]:
    """joint, y -> the one-freedom joint's value (rad or m)."""

    def value(joint: str, y: np.ndarray) -> float:
        k = mech.q_index(joint)
        return float(y[k]) if layout.euclidean else float(layout.q(y)[k])

    return value


def _events(drives: Drives, limits: Sequence[Limit], latches: Sequence[Latch], value) -> list[Event]:
    """The event functions of the joints not driven now: bounds (outwards) and latches."""
    driven = set(drives.all)
    out = []
    for lim in limits:
        if lim.joint not in driven:
            out.append(Event(f"upper:{lim.joint}", lambda t, y, j=lim.joint, b=lim.upper: value(j, y) - b, 1))
            out.append(Event(f"lower:{lim.joint}", lambda t, y, j=lim.joint, b=lim.lower: b - value(j, y), 1))
    for latch in latches:
        if latch.joint not in driven:
            sign = latch.direction or 1
            out.append(
                Event(
                    f"latch:{latch.joint}",
                    lambda t, y, j=latch.joint, x=latch.value, s=sign: s * (value(j, y) - x),
                    1 if latch.direction else 0,
                )
            )
    return out


def _act(
    event: str,
    system: MechanismSystem,
    recorder: Recorder,
    limits: Sequence[Limit],
    latches: Sequence[Latch],
    t: float,
    q: np.ndarray,
    v: np.ndarray,
    stopped: set[str],
) -> np.ndarray:
    """Apply an event at (t, q, v): the impact, and the joint held where it stops (a stop at a bound joins
    `stopped`); the velocities after it."""
    kind, joint = event.split(":", 1)
    jv = system.mech.v_index(joint)
    arrived = float(v[jv])
    if kind == "latch":
        bound, rate, hold = next(x.value for x in latches if x.joint == joint), 0.0, True
    else:
        lim = next(x for x in limits if x.joint == joint)
        bound = lim.upper if kind == "upper" else lim.lower
        rate = -lim.restitution * arrived
        hold = abs(rate) < REST_RATE
        rate = 0.0 if hold else rate
    _, drive_rates, _ = system.drives.at(t)
    jump = impact(system.cm, system.cd, q, v, system.drive_v, drive_rates, jv, rate)
    recorder.impulse(jump.drive_work, jump.dissipated)
    if hold:
        system.drives = system.drives.holding(joint, bound)
        recorder.holding(joint)
        if kind != "latch":
            stopped.add(joint)
    what = "latched" if kind == "latch" else ("stopped and held" if hold else f"bounced at {rate:.4g}")
    recorder.event(t, event, f"{what} (arrived at {arrived:.10g}, {jump.dissipated:.6g} J dissipated)")
    return jump.v


def _release(
    system: MechanismSystem,
    recorder: Recorder,
    limits: Sequence[Limit],
    t: float,
    q: np.ndarray,
    v: np.ndarray,
    stopped: set[str],
) -> None:
    """Release the joints stopped at a bound whose holding effort would pull them off it."""
    bounds = {x.joint: x for x in limits}
    held = sorted(stopped)
    if not held:
        return
    ev = system.evaluate(t, q, v)
    names = system.drives.all
    for joint in held:
        side = (
            1.0
            if abs(system.drives.held[joint] - bounds[joint].upper)
            < abs(system.drives.held[joint] - bounds[joint].lower)
            else -1.0
        )
        if side * ev.efforts[names.index(joint)] > 0:
            system.drives = system.drives.releasing(joint)
            stopped.discard(joint)
            recorder.event(t, f"release:{joint}", "released from its bound")


def _result(
    mech: Any, recorder: Recorder, elements: list[ForceElement], info: dict, inputs, with_reactions: bool
) -> SimulationResult:
    """The recorded samples as a `SimulationResult`, every sample's reactions from the core's inverse dynamics."""
    r = recorder.arrays()
    cm = mech.closure_model
    n, nj = len(r["t"]), len(cm.joint_names)
    reactions = np.full((n, nj, 6), np.nan)
    check = 0.0
    if with_reactions:
        for names, rows in recorder.groups().items():
            driven = cm.with_actuation(names)
            out = recorder.system_reactions(driven, rows, r)
            reactions[rows] = out.reactions
            cols = [recorder.effort_names.index(j) for j in names]
            check = max(check, float(np.max(np.abs(out.efforts - r["efforts"][rows][:, cols]), initial=0.0)))
        info["effort_check"] = check
    G, Jw, _ = core.kinematic_pass(cm, cm.create_data(), r["q"])
    axes = JointAxes(mech).world(Jw, G)
    source = getattr(inputs, "source", "") or ("prescribed inputs" if inputs is not None else "free motion")
    motion = MotionResult(
        mech.spec.name,
        f"simulation: {source}",
        r["t"],
        coordinate_names(mech.model),
        r["q"],
        r["v"],
        r["a"],
        tuple(recorder.effort_names),
        tuple(mech.actuated),
        r["efforts"],
        cm.joint_names,
        np.array(cm.supports, dtype=bool),
        reactions,
        axes,
    )
    friction = np.array([getattr(e, "friction", False) for e in elements], dtype=bool)
    return SimulationResult(
        motion,
        r["residual"],
        r["kinetic"],
        r["gravity"],
        tuple(e.name for e in elements),
        tuple(e.role for e in elements),
        r["potentials"],
        r["works"],
        r["drive_work"],
        r["impact_loss"],
        r["powers"][:, friction].sum(axis=1),
        tuple(recorder.events),
        info,
        run_momentum(mech.model, r["t"], r["q"], r["v"]),
    )
