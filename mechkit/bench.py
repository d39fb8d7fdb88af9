"""Speed and accuracy of every method, per mechanism and quantity (`mechkit bench`).

For each registered mechanism the engine draws a few assembled states near the home pose (inputs
offset by up to `INPUT_SPREAD`, random input rates and accelerations), computes the best reference
available for each quantity, then runs every method on those states: first once for its error,
then in a timed loop (one process, garbage collector off) for microseconds per call (median and
inter-quartile range over repeats).

Quantities and errors:

- "assembly": q from the input coordinates. Error max |q - q_ref| (rad or m, angles wrapped).
- "forward_dynamics": accelerations a under the reference efforts. Error max |a - a_ref| / max |a_ref|.
- "inverse_dynamics": efforts and joint reactions for (q, v, a). Error max |x - x_ref| / max |x_ref|
  over efforts and the reaction components that static equilibrium determines (the core's
  determinacy flags); moments of actuated joints are left out (they hold the effort, compared as
  such). A method that returns efforts only is compared on efforts ("efforts only").

References (the `reference` label of each table): the mechanism's own `BENCH_REFERENCE` (below) when
it has one; for four_bar and five_bar the closed-form kinematics and planar Newton-Euler of
`mechkit.validation.planar_linkages` (fully independent of Pinocchio); otherwise the core's own
tight solutions: closure Newton at 1e-13, a from the closure kinematics with tau from the core's
inverse dynamics (so forward dynamics is checked against inverse dynamics), and the core inverse
dynamics itself.

The ratio columns: "x fastest" = time / time of the fastest method whose error is at most
max(10 x this error, `EQUAL_ACCURACY_FLOOR`) (the fastest of equal or better accuracy; an
"efforts only" inverse dynamics is not counted against one that gives reactions); "x base" =
time / time of the quantity's baseline (`BASELINES`: the core's default method).

BENCH_METHODS protocol (optional, in `mechkit/mechanisms/<name>.py`)::

    BENCH_METHODS = {
        "assembly": [("paper closed form", lambda mech, s: q)],            # -> (nq,) q
        "forward_dynamics": [("...", lambda mech, s: a)],                   # -> (nv,) a
        "inverse_dynamics": [("SOC (numpy)", lambda mech, s: result)],      # -> efforts (+ reactions)
    }
    BENCH_REFERENCE = {"inverse_dynamics": lambda mech, s: result}        # best independent reference

Each callable takes the `Mechanism` and a `Sample` (fields `inputs`, `rates`, `accelerations` in
actuated order; `q`, `v`, `a`, `tau` (nv,) joint vectors; `extra` dict for cached data). An
inverse-dynamics result is any object or dict with `efforts` ({actuated joint: N m or N}) and
optionally `reactions` ({joint: (6,) world wrench [f, m] parent on child at the joint origin, or a
`JointReaction`}). A callable may raise a `MechkitError`: the table then shows it as the outcome.
"""

from __future__ import annotations

import gc
import importlib
import os
import platform
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mechkit.exceptions import MechkitError, MethodUnavailable

QUANTITIES = ("assembly", "forward_dynamics", "inverse_dynamics")
ERROR_LABELS = {
    "assembly": "max |q - q_ref| (rad or m)",
    "forward_dynamics": "max |a - a_ref| / max |a_ref| (-)",
    "inverse_dynamics": "max relative error of efforts and determinate reactions (-)",
}
BASELINES = {"assembly": "closure Newton tol=1e-12", "forward_dynamics": "constraintDynamics mu=1e-09 it=20",
             "inverse_dynamics": "constrained RNEA + determinacy"}
#: Errors at or below this count as one accuracy class (machine precision) for the ratio column.
EQUAL_ACCURACY_FLOOR = 1e-12
#: Largest offset of the sampled inputs from the home inputs (rad or m).
INPUT_SPREAD = 0.05
#: Error shown on log charts for an exact result.
CHART_FLOOR = 1e-17
#: How to read the peers' rows (docs/benchmarks.md).
PEER_NOTES = """\
- MuJoCo runs the MJCF of `mechkit export NAME --format mjcf` (same tree, `equality` connect/weld at
  the cuts). Its equality constraints are soft: at the default solref/solimp the closure gives way.
  At rest the four-bar's accelerations are off by ~1 % of their gravity-driven size (~1e2 rad/s^2);
  the bench's states move slowly (|a| ~ 1 rad/s^2, the efforts holding gravity), so the same softness
  reads as an O(1)-O(10) relative error here. "Stiff" (impedance 0.9999, time constant 2 ms) narrows
  it to ~1e-5 of the gravity scale.
  `mj_forward` is timed with the efforts as `qfrc_applied`. Its inverse dynamics row is
  `mj_inverse` plus our least-squares split of M a + c on MuJoCo's constraint Jacobian (MuJoCo has no
  such split): it is exact because the split is, and reports efforts only.
- Drake (when installed: `pip install drake`) runs a discrete `MultibodyPlant` (SAP, dt = 1 ms) with
  ball constraints at the cuts; the row is (v_next - v) / dt of one step. SAP imposes the closure on
  the next velocity at the current configuration, so one step misses the velocity-product term of
  the closure acceleration (J a = -J'v): its error does not shrink with dt at states with velocity.
  It exposes no constraint force (no reactions).
- The core's inverse-dynamics rows give every joint's reaction; the numpy methods of four_bar and
  five_bar start from the link motion of the closed form (their times exclude that conversion).
"""


# ---------------------------------------------------------------------------- data
@dataclass
class Sample:
    """One assembled state of a mechanism (SI units, mechkit's joint vectors).

    `inputs`, `rates`, `accelerations` are values of `input_names`: the actuated joints, then extra
    joints when the actuators alone do not fix the configuration (under-actuated mechanisms).
    """

    inputs: np.ndarray
    rates: np.ndarray
    accelerations: np.ndarray
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    tau: np.ndarray
    input_names: tuple[str, ...] = ()
    extra: dict[str, Any] = field(default_factory=dict)


@dataclass
class IDReference:
    """Reference inverse dynamics at one sample: efforts, reactions and which components to compare."""

    efforts: dict[str, float]
    reactions: dict[str, np.ndarray]
    determinate: dict[str, np.ndarray]


@dataclass
class References:
    """Per quantity: a label and one reference value per sample."""

    labels: dict[str, str]
    q: list[np.ndarray]
    a: list[np.ndarray]
    inverse: list[IDReference]


@dataclass(frozen=True)
class Method:
    """One way to compute a quantity.

    Attributes:
        name: label in tables and charts (unique per quantity).
        quantity: one of `QUANTITIES`.
        run: (mechanism, sample) -> result.
        family: points of one family are joined on the charts (an accuracy knob swept).
        peer: a peer simulator's method (marked in tables).
        knob: the swept setting of this point, written beside it on the charts.
    """

    name: str
    quantity: str
    run: Callable[[Any, Sample], Any]
    family: str = ""
    peer: bool = False
    knob: str = ""


@dataclass
class Row:
    """The measurement of one method on one mechanism."""

    mechanism: str
    method: Method
    median_s: float = float("nan")
    p25_s: float = float("nan")
    p75_s: float = float("nan")
    error: float = float("nan")
    outcome: str = "ok"
    note: str = ""
    x_fastest: float = float("nan")
    x_base: float = float("nan")


@dataclass
class MechanismBench:
    """All rows of one mechanism, with its references and size."""

    name: str
    nv: int
    rows_closure: int
    references: dict[str, str]
    rows: list[Row]
    paired: dict[str, float] = field(default_factory=dict)
    mech: Any = None
    samples: list[Sample] = field(default_factory=list)


# ---------------------------------------------------------------------------- progress
class Progress:
    """A one-line progress bar on stderr, shown only on a terminal or when MECHKIT_PROGRESS=1."""

    def __init__(self, total: int, label: str, enabled: bool | None = None):
        if enabled is None:
            enabled = sys.stderr.isatty() or os.environ.get("MECHKIT_PROGRESS") == "1"
        self.total, self.label, self.enabled, self.done = max(total, 1), label, enabled, 0

    def step(self, what: str = "") -> None:
        self.done += 1
        if self.enabled:
            width = 30
            filled = int(width * self.done / self.total)
            sys.stderr.write(f"\r{self.label} [{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} {what[:40]:<40}")
            if self.done >= self.total:
                sys.stderr.write("\n")
            sys.stderr.flush()


# ---------------------------------------------------------------------------- timing
def time_per_call(fn: Callable[[Sample], Any], samples: Sequence[Sample], budget_s: float, repeats: int) -> np.ndarray:
    """Seconds per call of fn cycling over the samples: one value per repeat.

    The loop count is calibrated so that each repeat lasts about budget_s / repeats.
    """
    gc_was = gc.isenabled()
    gc.disable()
    try:
        t0 = time.perf_counter()
        fn(samples[0])
        once = max(time.perf_counter() - t0, 1e-7)
        loops = max(1, int(budget_s / repeats / once))
        n = len(samples)
        out = np.empty(repeats)
        for r in range(repeats):
            start = time.perf_counter_ns()
            for i in range(loops):
                fn(samples[i % n])
            out[r] = (time.perf_counter_ns() - start) * 1e-9 / loops
    finally:
        if gc_was:
            gc.enable()
    return out


def paired_ratio(fa: Callable[[Sample], Any], fb: Callable[[Sample], Any], samples: Sequence[Sample],
                 budget_s: float, repeats: int) -> float:
    """Median over repeats of t(fa) / t(fb), the two timed back to back in each repeat (load cancels)."""
    ratios = [time_per_call(fa, samples, budget_s / repeats / 2, 1)[0] / time_per_call(fb, samples, budget_s / repeats / 2, 1)[0]
              for _ in range(repeats)]
    return float(np.median(ratios))


# ---------------------------------------------------------------------------- errors
def _wrap(x: np.ndarray) -> np.ndarray:
    return (x + np.pi) % (2.0 * np.pi) - np.pi


def assembly_error(q: np.ndarray, q_ref: np.ndarray) -> float:
    """max |q - q_ref| with angle differences wrapped to (-pi, pi] (rad or m)."""
    return float(np.max(np.abs(_wrap(np.asarray(q) - q_ref))))


def acceleration_error(a: np.ndarray, a_ref: np.ndarray) -> float:
    """max |a - a_ref| / max |a_ref| (a_ref scale floored at 1e-300)."""
    a = np.asarray(a, dtype=float)
    if not np.all(np.isfinite(a)):
        raise FloatingPointError("non-finite accelerations")
    return float(np.max(np.abs(a - a_ref)) / max(np.max(np.abs(a_ref)), 1e-300))


def _id_parts(result: Any) -> tuple[dict[str, float], dict[str, np.ndarray] | None]:
    get = result.get if isinstance(result, dict) else (lambda k, d=None: getattr(result, k, d))
    efforts = get("efforts")
    reactions = get("reactions", None)
    if efforts is None:
        raise TypeError("an inverse-dynamics result needs 'efforts'")
    if reactions is not None:
        reactions = {k: np.asarray(getattr(r, "wrench", r), dtype=float) for k, r in reactions.items()}
    return dict(efforts), reactions


def inverse_error(result: Any, ref: IDReference, actuated: Sequence[str]) -> tuple[float, str]:
    """Relative error of efforts and determinate reaction components, and a note ("efforts only", ...)."""
    efforts, reactions = _id_parts(result)
    scale = max([abs(u) for u in ref.efforts.values()] + [float(np.max(np.abs(w))) for w in ref.reactions.values()] + [1e-300])
    worst = max(abs(efforts[j] - u) for j, u in ref.efforts.items())
    if reactions is None:
        return worst / scale, "efforts only"
    compared = 0
    for joint, wrench in ref.reactions.items():
        if joint not in reactions:
            continue
        mask = ref.determinate[joint].copy()
        if joint in actuated:
            mask[3:] = False
        if mask.any():
            worst = max(worst, float(np.max(np.abs(reactions[joint][mask] - wrench[mask]))))
            compared += 1
    note = "" if compared == len(ref.reactions) else f"{compared}/{len(ref.reactions)} reactions"
    return worst / scale, note


# ---------------------------------------------------------------------------- samples and references
def input_joints(mech) -> tuple[str, ...]:
    """The actuated joints, then (under-actuated mechanisms) extra joints completing a set of independent coordinates."""
    from scipy.linalg import null_space

    names = list(mech.actuated)
    dof = mech.mobility().dof
    if len(names) >= dof:
        return tuple(names)
    basis = null_space(mech.closure_jacobian(mech.home_q))
    chosen = [mech.v_index(j) for j in names]
    for joint in mech.model.names[1:]:
        if len(chosen) == dof:
            break
        trial = chosen + [mech.v_index(joint)]
        if joint not in names and np.linalg.matrix_rank(basis[trial]) == len(trial):
            chosen, names = trial, names + [joint]
    return tuple(names)


def _scene_configurations(mech, count: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """Up to `count` (configuration, the scene's previous configuration) pairs spread along the first
    scene the module defines; the previous one is the assembly's warm start."""
    from mechkit.viz import own_scenes

    for scene in own_scenes(mech).values():
        poses = [np.asarray(q, dtype=float) for q in scene(mech)]
        picks = np.linspace(1, len(poses) - 1, min(count, len(poses) - 1)).round().astype(int)
        return [(poses[i], poses[i - 1]) for i in picks]
    return []


def _closes(mech, q: np.ndarray, v: np.ndarray, a: np.ndarray) -> bool:
    """Whether a satisfies the acceleration-level closure J a + gamma = 0 to 1e-9 (relative)."""
    J = mech.closure_jacobian(q)
    gamma = mech.closure_drift(q, v)
    return bool(np.max(np.abs(J @ a + gamma), initial=0.0) <= 1e-9 * max(np.max(np.abs(J), initial=0.0) * np.max(np.abs(a)),
                                                                             np.max(np.abs(gamma), initial=0.0), 1e-12))


def make_samples(mech, count: int, seed: int = 7) -> list[Sample]:
    """`count` assembled states near home (closure tolerance 1e-12).

    Inputs within INPUT_SPREAD of home (divided by 5 until the linkage assembles), then, if too few
    assemble, configurations along the module's first scene; input rates ~ N(0, 0.5).
    Fully actuated: input accelerations ~ N(0, 1) and a from the closure kinematics (tau is set by
    `references`). Under-actuated, or where that a does not satisfy J a + gamma = 0 to 1e-9 (a rank
    change near home): efforts ~ N(0, generalised gravity scale) on the actuators and a from the
    core's dense KKT forward dynamics (the inverse dynamics must give those efforts back).
    """
    import pinocchio as pin

    rng = np.random.default_rng(seed)
    names = input_joints(mech)
    under = len(names) > len(mech.actuated)
    act_v = [mech.v_index(j) for j in mech.actuated]
    home = np.array([mech.home_q[mech.q_index(j)] for j in names])
    out: list[Sample] = []
    why = ""
    data = mech.model.createData()
    def add(q: np.ndarray, guess: np.ndarray) -> None:
        """Moving state at q: random input rates; accelerations from the closure, else from the dynamics.
        `guess` is where the assembly methods start from."""
        inputs = np.array([q[mech.q_index(j)] for j in names])
        rates = rng.normal(0.0, 0.5, home.size)
        accs = rng.normal(0.0, 1.0, home.size)
        v = mech.velocities(q, rates, inputs=names)
        tau = np.zeros(mech.model.nv)
        a = None if under else mech.accelerations(q, v, accs, inputs=names)
        if a is not None and not _closes(mech, q, v, a):
            a = None  # the projection is inconsistent here (second-order mobility): use the dynamics
        if a is None:
            scale = max(float(np.max(np.abs(pin.computeGeneralizedGravity(mech.model, data, q)[act_v]))), 1e-3)
            tau[act_v] = rng.normal(0.0, scale, len(act_v))
            a = mech.forward_dynamics(q, v, tau, "kkt").a
            accs = a[[mech.v_index(j) for j in names]]
        sample = Sample(inputs, rates, accs, q, v, a, tau, tuple(names))
        if tau.any():
            sample.extra["efforts"] = {j: float(tau[i]) for j, i in zip(mech.actuated, act_v)}
        sample.extra["guess"] = guess
        out.append(sample)

    for spread in (INPUT_SPREAD, INPUT_SPREAD / 5, INPUT_SPREAD / 25):
        for _ in range(count * 2):
            if len(out) == count:
                break
            try:
                q = mech.assemble(dict(zip(names, home + rng.uniform(-spread, spread, home.size))), guess=mech.home_q)
                add(q, mech.home_q)
            except MechkitError as err:
                why = str(err)
    if len(out) < count:
        # some linkages do not assemble for arbitrary inputs near home (the deployable's seventh DOF
        # exists only along symmetric folds): take states along the module's own scene instead
        for q, previous in _scene_configurations(mech, count - len(out)):
            try:
                add(q, previous)
            except MechkitError as err:
                why = str(err)
    if not out:
        raise MethodUnavailable("bench samples", f"no state near home of {mech.spec.name}: {why}")
    return out


def _core_inverse_reference(mech, s: Sample) -> IDReference:
    r = mech.inverse_dynamics(s.q, s.v, s.a, determinacy=True)
    return IDReference(dict(s.extra.get("efforts", r.efforts)), {k: x.wrench for k, x in r.reactions.items()},
                       {k: x.determinate for k, x in r.reactions.items()})


def references(mech, samples: list[Sample], extras: dict[str, Any]) -> References:
    """The best reference per quantity; sets each sample's tau to the reference efforts."""
    labels = {"assembly": "closure Newton at 1e-14 (or the tightest reached, core)",
              "forward_dynamics": "closure kinematics a, tau from the inverse-dynamics reference",
              "inverse_dynamics": "core constrained RNEA (determinacy on)"}
    core = [_core_inverse_reference(mech, s) for s in samples]
    if "efforts" in samples[0].extra:
        labels["forward_dynamics"] = "core dense KKT on independent rows (under-actuated, or kinematic a inconsistent)"
        labels["inverse_dynamics"] = "the efforts that produced a (forward/inverse round trip); reactions: core"
    q_ref = [s.q.copy() for s in samples]
    a_ref = [s.a.copy() for s in samples]
    inverse = core
    custom = extras.get("reference", {})
    if "assembly" in custom:
        labels["assembly"], fn = custom["assembly"]
        q_ref = [np.asarray(fn(mech, s), dtype=float) for s in samples]
    if "forward_dynamics" in custom:
        labels["forward_dynamics"], fn = custom["forward_dynamics"]
        a_ref = [np.asarray(fn(mech, s), dtype=float) for s in samples]
    if "inverse_dynamics" in custom:
        labels["inverse_dynamics"], fn = custom["inverse_dynamics"]
        inverse = []
        for s, c in zip(samples, core):
            efforts, reactions = _id_parts(fn(mech, s))
            reactions = reactions or {}
            inverse.append(IDReference(efforts, reactions, {k: c.determinate[k] for k in reactions if k in c.determinate}))
    for s, ref in zip(samples, inverse):
        if "efforts" not in s.extra:
            s.tau = np.zeros(mech.model.nv)
            for joint, u in ref.efforts.items():
                s.tau[mech.v_index(joint)] = u
    return References(labels, q_ref, a_ref, inverse)


# ---------------------------------------------------------------------------- methods
def core_methods(mech, quick: bool) -> list[Method]:
    """The core's methods with their accuracy knobs swept."""
    import pinocchio as pin

    methods = []
    tols = (1e-6, 1e-12) if quick else (1e-4, 1e-6, 1e-9, 1e-12)
    for algo, label in (("newton", "closure Newton"), ("lm", "closure LM")):
        for tol in tols:
            methods.append(Method(f"{label} tol={tol:g}", "assembly",
                                  lambda m, s, algo=algo, tol=tol: m.assemble(dict(zip(s.input_names, s.inputs)), guess=s.extra["guess"],
                                                                              tol=tol, method=algo),
                                  family=label, knob=f"tol={tol:g}"))
    mus = (1e-9, 1e-3) if quick else (1e-12, 1e-9, 1e-6, 1e-3)
    iters = (1, 20) if quick else (1, 3, 20)
    try:
        mech.pin_constraints()
        proximal = True
    except MechkitError:
        proximal = False
    if proximal:
        for it in iters:
            for mu in mus:
                methods.append(Method(f"constraintDynamics mu={mu:g} it={it}", "forward_dynamics",
                                      lambda m, s, mu=mu, it=it: m.forward_dynamics(s.q, s.v, s.tau, "proximal", mu=mu, max_iter=it).a,
                                      family=f"constraintDynamics it={it}", knob=f"mu={mu:g}"))
        cms, cds = mech.pin_constraints()
        raw_data = mech.model.createData()
        pin.initConstraintDynamics(mech.model, raw_data, cms, cds)
        prox = pin.ProximalSettings(1e-12, 1e-9, 20)
        methods.append(Method("raw pin.constraintDynamics (mu=1e-9)", "forward_dynamics",
                              lambda m, s: pin.constraintDynamics(m.model, raw_data, s.q, s.v, s.tau, cms, cds, prox)))
    methods.append(Method("dense KKT (independent rows)", "forward_dynamics",
                          lambda m, s: m.forward_dynamics(s.q, s.v, s.tau, "kkt").a))
    methods.append(Method("constrained RNEA + determinacy", "inverse_dynamics",
                          lambda m, s: m.inverse_dynamics(s.q, s.v, s.a, determinacy=True)))
    methods.append(Method("constrained RNEA, no determinacy", "inverse_dynamics",
                          lambda m, s: m.inverse_dynamics(s.q, s.v, s.a, determinacy=False)))
    return methods


def peer_methods(mech) -> tuple[list[Method], list[str]]:
    """MuJoCo (default and stiff) and Drake rows; unavailable peers come back as notes."""
    from mechkit import peers

    methods, notes = [], []
    for stiff, label in ((False, "default"), (True, "stiff")):
        try:
            p = peers.MujocoPeer(mech, stiff=stiff)
        except MechkitError as err:
            notes.append(f"MuJoCo {label}: {err}")
            continue
        methods.append(Method(f"MuJoCo mj_forward ({label} solref/solimp)", "forward_dynamics",
                              lambda m, s, p=p: p.forward(s.q, s.v, s.tau), family="MuJoCo", peer=True, knob=label))
        if not stiff:
            methods.append(Method("MuJoCo mj_inverse + split on efc_J", "inverse_dynamics",
                                  lambda m, s, p=p: {"efforts": p.inverse(s.q, s.v, s.a)}, peer=True))
    try:
        d = peers.DrakePeer(mech)
        methods.append(Method(f"Drake SAP step (dt={peers.DRAKE_DT:g})", "forward_dynamics",
                              lambda m, s, d=d: d.forward(s.q, s.v, s.tau), peer=True))
    except MechkitError as err:
        notes.append(f"Drake: {err}")
    return methods, notes


def module_extras(mech) -> dict[str, Any]:
    """BENCH_METHODS / BENCH_REFERENCE of the mechanism's module, plus the built-in planar ones."""
    from mechkit import bench_planar

    module = importlib.import_module(f"mechkit.mechanisms.{mech.spec.name}")
    methods = {q: list(v) for q, v in getattr(module, "BENCH_METHODS", {}).items()}
    reference = {}
    for q, fn in getattr(module, "BENCH_REFERENCE", {}).items():
        reference[q] = (getattr(fn, "__doc__", None) or f"{mech.spec.name} BENCH_REFERENCE").strip().splitlines()[0], fn
    builtin = bench_planar.extras(mech)
    for q, v in builtin.get("methods", {}).items():
        methods.setdefault(q, []).extend(v)
    for q, v in builtin.get("reference", {}).items():
        reference.setdefault(q, v)
    unknown = set(methods) - set(QUANTITIES)
    if unknown:
        raise MethodUnavailable(f"{mech.spec.name}.BENCH_METHODS", f"unknown quantities {sorted(unknown)}; use {QUANTITIES}")
    return {"methods": methods, "reference": reference}


# ---------------------------------------------------------------------------- measuring
def measure(mech, method: Method, samples: list[Sample], refs: References, budget_s: float, repeats: int) -> Row:
    """Error on every sample, then time per call; a raised MechkitError becomes the row's outcome."""
    row = Row(mech.spec.name, method)
    errors = []
    try:
        for i, s in enumerate(samples):
            result = method.run(mech, s)
            if method.quantity == "assembly":
                errors.append(assembly_error(result, refs.q[i]))
            elif method.quantity == "forward_dynamics":
                errors.append(acceleration_error(result, refs.a[i]))
            else:
                err, row.note = inverse_error(result, refs.inverse[i], mech.actuated)
                errors.append(err)
    except (MechkitError, FloatingPointError, np.linalg.LinAlgError, TypeError) as err:
        row.outcome = f"raises {type(err).__name__}: {err}"
        return row
    except Exception as err:  # a peer's own failure is its row's outcome; ours propagate
        if not method.peer:
            raise
        row.outcome = f"raises {type(err).__name__}: {err}"
        return row
    row.error = max(errors)
    if not np.isfinite(row.error):
        row.outcome = "non-finite result"
        return row
    times = time_per_call(lambda s: method.run(mech, s), samples, budget_s, repeats)
    row.median_s = float(np.median(times))
    row.p25_s, row.p75_s = (float(x) for x in np.percentile(times, [25, 75]))
    return row


def _ratios(rows: list[Row]) -> None:
    for quantity in QUANTITIES:
        ok = [r for r in rows if r.method.quantity == quantity and r.outcome == "ok"]
        base = [r for r in ok if r.method.name == BASELINES[quantity]]
        for r in ok:
            limit = max(10.0 * r.error, EQUAL_ACCURACY_FLOOR)
            # a method that gives efforts only is no yardstick for one that gives every reaction
            candidates = [o for o in ok if o.error <= limit and (o.note != "efforts only" or r.note == "efforts only")]
            r.x_fastest = r.median_s / min(o.median_s for o in candidates)
            if base:
                r.x_base = r.median_s / base[0].median_s


def bench_mechanism(name: str, quick: bool = True, with_peers: bool = True, progress: bool | None = None) -> MechanismBench:
    """Every method on one mechanism, measured in this process.

    Args:
        progress: show a progress bar over the methods on stderr (None: only on a terminal or with
            MECHKIT_PROGRESS=1).
    """
    import mechkit

    mech = mechkit.load(name)
    samples = make_samples(mech, 3 if quick else 8)
    extras = module_extras(mech)
    refs = references(mech, samples, extras)
    methods = core_methods(mech, quick)
    for quantity, entries in extras["methods"].items():
        for entry in entries:
            methods.append(entry if isinstance(entry, Method) else Method(entry[0], quantity, entry[1]))
    notes: list[str] = []
    if with_peers:
        peer, notes = peer_methods(mech)
        methods += peer
    budget, repeats = (0.03, 5) if quick else (0.3, 15)
    rows = []
    bar = Progress(len(methods), name, progress)
    for method in methods:
        rows.append(measure(mech, method, samples, refs, budget, repeats))
        bar.step(method.name)
    _ratios(rows)
    paired = _paired(mech, rows, samples, budget * 4, max(repeats, 7))
    labels = dict(refs.labels)
    for note in notes:
        labels.setdefault("peers", "")
        labels["peers"] = (labels["peers"] + "; " if labels["peers"] else "") + note
    return MechanismBench(name, mech.model.nv, mech.rows.size, labels, rows, paired, mech, samples)


#: The goals' pairs (numerator, denominator), timed back to back by `paired_ratio`.
GOAL_PAIRS = {
    "fd/mujoco": (BASELINES["forward_dynamics"], "MuJoCo mj_forward (default solref/solimp)"),
    "id/mujoco": ("constrained RNEA, no determinacy", "MuJoCo mj_forward (default solref/solimp)"),
    "id/raw": ("constrained RNEA, no determinacy", "raw pin.constraintDynamics (mu=1e-9)"),
    "id+det/raw": (BASELINES["inverse_dynamics"], "raw pin.constraintDynamics (mu=1e-9)"),
    "raw/mujoco": ("raw pin.constraintDynamics (mu=1e-9)", "MuJoCo mj_forward (default solref/solimp)"),
}


def _paired(mech, rows: list[Row], samples: list[Sample], budget: float, repeats: int) -> dict[str, float]:
    ok = {r.method.name: r.method for r in rows if r.outcome == "ok"}
    out = {}
    for key, (a, b) in GOAL_PAIRS.items():
        if a in ok and b in ok:
            out[key] = paired_ratio(lambda s, f=ok[a].run: f(mech, s), lambda s, f=ok[b].run: f(mech, s), samples, budget, repeats)
    return out


# ---------------------------------------------------------------------------- output
def _us(x: float) -> str:
    return "-" if not np.isfinite(x) else f"{x * 1e6:.2f}"


def _num(x: float, fmt: str = ".1e") -> str:
    return "-" if not np.isfinite(x) else format(x, fmt)


def format_table(b: MechanismBench, markdown: bool = False) -> str:
    """The per-mechanism table (plain text or GitHub markdown)."""
    head = ["quantity", "method", "us/call", "IQR us", "error", "x fastest", "x base", "outcome"]
    lines = []
    body = []
    for r in b.rows:
        iqr = r.p75_s - r.p25_s
        outcome = r.outcome if r.outcome != "ok" else (r.note or "ok")
        name = ("[peer] " if r.method.peer else "") + r.method.name
        body.append([r.method.quantity, name, _us(r.median_s), _us(iqr), _num(r.error), _num(r.x_fastest, ".2f"),
                     _num(r.x_base, ".2f"), outcome])
    if markdown:
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "---|" * len(head))
        lines += ["| " + " | ".join(c.replace("|", "/") for c in row) + " |" for row in body]
    else:
        widths = [max(len(h), *(len(row[i]) for row in body)) for i, h in enumerate(head[:-1])]
        fmt = "  ".join(f"{{:<{w}}}" for w in widths) + "  {}"
        lines.append(fmt.format(*head))
        lines += [fmt.format(*row) for row in body]
    refs = "; ".join(f"{q}: {label}" for q, label in b.references.items())
    title = f"{b.name} (nv={b.nv}, closure rows={b.rows_closure})"
    if markdown:
        return f"### {title}\n\nReferences: {refs}.\n\n" + "\n".join(lines) + "\n"
    return f"== {title}\nreferences: {refs}\n" + "\n".join(lines) + "\n"


def machine() -> dict[str, str]:
    """Machine and versions, for the record."""
    import numpy
    import pinocchio
    import scipy

    info = {"python": platform.python_version(), "platform": platform.platform(), "processor": _cpu(),
            "cores": str(os.cpu_count()), "pinocchio": pinocchio.__version__, "numpy": numpy.__version__,
            "scipy": scipy.__version__}
    from importlib import metadata

    for dist in ("mujoco", "drake", "matplotlib"):
        try:
            info[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            info[dist] = "not installed"
    return info


def _cpu() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def goals(results: list[MechanismBench]) -> list[str]:
    """The issue's two goals, from back-to-back (paired) timings: one line per mechanism and goal."""
    out = []
    for b in results:
        by = {r.method.name: r for r in b.rows if r.outcome == "ok"}
        mj = by.get("MuJoCo mj_forward (default solref/solimp)")
        fd = by.get(BASELINES["forward_dynamics"])
        idr = by.get("constrained RNEA, no determinacy")
        p = b.paired
        if mj and fd and "fd/mujoco" in p:
            acc = mj.error / max(fd.error, 1e-300)
            id_ratio = p.get("id/mujoco", float("inf"))
            met = p["fd/mujoco"] <= 1.0 and id_ratio <= 1.0 and acc >= 1e6
            raw_ok = p.get("raw/mujoco", float("inf")) <= 1.0
            missed = [what for what, bad in (
                ("forward dynamics slower" + (": the raw Pinocchio call is faster than MuJoCo, the wrapper's Python overhead is not"
                                              if raw_ok else ": the raw pin.constraintDynamics itself is slower here (legacy "
                                              "proximal path, see the scale fit)"), p["fd/mujoco"] > 1.0),
                ("reactions slower: Python overhead of the core's inverse dynamics, see tools/bench_core.py --profile",
                 id_ratio > 1.0), ("accuracy < 1e6x", acc < 1e6)) if bad]
            raw = f" (raw pin.constraintDynamics {p['raw/mujoco']:.2f})" if "raw/mujoco" in p else ""
            out.append(f"{b.name}: time / MuJoCo mj_forward: constrained forward dynamics {p['fd/mujoco']:.2f}{raw}, inverse "
                       f"dynamics with reactions {id_ratio:.2f}; error {fd.error:.1e} vs MuJoCo default {mj.error:.1e} "
                       f"({acc:.1e}x): {'MET' if met else 'MISSED (' + ', '.join(missed) + ')'}")
        if "id/raw" in p:
            det = f", with determinacy {p['id+det/raw']:.1f}x" if "id+det/raw" in p else ""
            err = f" (error {idr.error:.1e})" if idr else ""
            out.append(f"{b.name}: inverse dynamics with every reaction / one raw pin.constraintDynamics: "
                       f"{p['id/raw']:.1f}x{err}{det}: "
                       + ("MET (goal 5x)" if p["id/raw"] <= 5 else "MISSED (goal 5x): Python-level numpy work around the "
                          "Pinocchio calls dominates, see tools/bench_core.py --profile"))
    return out


#: Core methods timed for the cost-vs-size fit.
SCALE_METHODS = (BASELINES["assembly"], BASELINES["forward_dynamics"], "raw pin.constraintDynamics (mu=1e-9)",
                 "dense KKT (independent rows)", BASELINES["inverse_dynamics"], "constrained RNEA, no determinacy")


def goal_summary(results: list[MechanismBench]) -> str:
    """One paragraph: how many mechanisms meet each goal, from the paired timings."""
    n = len(results)
    p = [b.paired for b in results]
    fd = sum(1 for x in p if x.get("fd/mujoco", np.inf) <= 1.0)
    raw = sum(1 for x in p if x.get("raw/mujoco", np.inf) <= 1.0)
    idm = sum(1 for x in p if x.get("id/mujoco", np.inf) <= 1.0)
    inaccurate = []
    for b in results:
        by = {r.method.name: r for r in b.rows if r.outcome == "ok"}
        mj, ours = by.get("MuJoCo mj_forward (default solref/solimp)"), by.get(BASELINES["forward_dynamics"])
        if not (mj and ours and mj.error >= 1e6 * ours.error):
            inaccurate.append(b.name)
    acc = n - len(inaccurate)
    idr = sum(1 for x in p if x.get("id/raw", np.inf) <= 5.0)
    return (f"Goal 1 (our constrained dynamics and reactions at least as fast as MuJoCo's forward step, 1e6x more "
            f"accurate than its default soft constraints): accuracy met on {acc}/{n}"
            + (f" (missed: {', '.join(inaccurate)}: see its table, our own methods disagree there)" if inaccurate else "")
            + f"; speed of the forward-dynamics "
            f"wrapper met on {fd}/{n} (the raw pin.constraintDynamics call on {raw}/{n}); inverse dynamics with every "
            f"reaction as fast as mj_forward on {idm}/{n}. Goal 2 (inverse dynamics with every reaction within 5x of "
            f"one raw pin.constraintDynamics): met on {idr}/{n}. Where speed is missed, the cost is Python-level work around "
            f"the Pinocchio calls (see tools/bench_core.py --profile), except where the raw "
            f"pin.constraintDynamics call is itself slower than mj_forward ({n - raw}/{n}: Pinocchio's legacy proximal "
            f"path: see its exponent in the scale fit).")


def scale_fits(results: list[MechanismBench], budget_s: float = 0.02, rounds: int = 7
               ) -> list[tuple[str, list[tuple[str, int, float]], float]]:
    """Cost vs model size: per method of SCALE_METHODS, (method, [(mechanism, nv, seconds)], exponent p of t ~ nv^p).

    The mechanisms are timed round-robin (each round times every mechanism once) so that a change
    of machine load hits all of them alike; the median over rounds is fitted by least squares in
    log-log. Methods measured on fewer than 3 mechanisms are left out.
    """
    out = []
    for name in SCALE_METHODS:
        runs = [(b, r.method) for b in results for r in b.rows if r.method.name == name and r.outcome == "ok" and b.mech is not None]
        if len(runs) < 3:
            continue
        times = np.empty((rounds, len(runs)))
        for k in range(rounds):
            for i, (b, method) in enumerate(runs):
                times[k, i] = time_per_call(lambda s, b=b, f=method.run: f(b.mech, s), b.samples, budget_s, 1)[0]
        med = np.median(times, axis=0)
        pts = sorted(((b.name, b.nv, float(t)) for (b, _), t in zip(runs, med)), key=lambda p: p[1])
        nvs = np.array([p[1] for p in pts], dtype=float)
        if np.ptp(np.log(nvs)) > 0:
            slope = float(np.polyfit(np.log(nvs), np.log([p[2] for p in pts]), 1)[0])
            out.append((name, pts, slope))
    return out


def pyplot():
    """matplotlib.pyplot on the Agg backend (files only, no window)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig, ax, folder: Path, stem: str, legend_size: int = 6) -> list[Path]:
    """Grid, legend, tight layout; write `folder/stem.png` and `.svg`; close the figure."""
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=legend_size)
    fig.tight_layout()
    folder.mkdir(parents=True, exist_ok=True)
    paths = [folder / f"{stem}.{ext}" for ext in ("png", "svg")]
    for p in paths:
        fig.savefig(p, dpi=90)
    pyplot().close(fig)
    return paths


def chart(b: MechanismBench, quantity: str, folder: Path) -> list[Path]:
    """Error vs time per call, log-log, one point per method, knob sweeps joined; PNG and SVG."""
    plt = pyplot()

    rows = [r for r in b.rows if r.method.quantity == quantity and r.outcome == "ok"]
    failed = [r for r in b.rows if r.method.quantity == quantity and r.outcome != "ok"]
    if not rows:
        return []
    fig, ax = plt.subplots(figsize=(8, 5.5))
    families: dict[str, list[Row]] = {}
    for r in rows:
        families.setdefault(r.method.family or r.method.name, []).append(r)
    markers = "osD^v<>ph*X"
    for k, (family, members) in enumerate(families.items()):
        t = np.array([r.median_s * 1e6 for r in members])
        e = np.array([max(r.error, CHART_FLOOR) for r in members])
        peer = members[0].method.peer
        style = {"marker": "s" if peer else markers[k % len(markers)], "markersize": 7,
                 "linestyle": "--" if peer else "-", "markerfacecolor": "none" if peer else None}
        label = ("[peer] " if peer else "") + family
        if len(members) > 1:
            ax.plot(t, e, label=label, **style)
            for r, ti, ei in zip(members, t, e):
                ax.annotate(r.method.knob or r.method.name, (ti, ei), fontsize=6, xytext=(3, 3), textcoords="offset points")
        else:
            style["linestyle"] = "none"
            ax.plot(t, e, label=label, **style)
    ax.axhline(CHART_FLOOR, color="grey", lw=0.5, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per call (microseconds, median)")
    ax.set_ylabel(f"error: {ERROR_LABELS[quantity]}")
    title = f"{b.name}: {quantity.replace('_', ' ')} (reference: {b.references.get(quantity, '?')})"
    ax.set_title(title if len(title) < 95 else title[:92] + "...", fontsize=9)
    if failed:
        ax.text(0.01, 0.01, "raised: " + "; ".join(r.method.name for r in failed)[:150], transform=ax.transAxes, fontsize=6)
    return save_figure(fig, ax, folder, f"bench_{b.name}_{quantity}", legend_size=7)


def scale_chart(fits, folder: Path) -> list[Path]:
    """Cost vs model size (nv), log-log, one curve per method, fitted exponent in the legend."""
    plt = pyplot()

    if not fits:
        return []
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for name, pts, slope in fits:
        ax.plot([p[1] for p in pts], [p[2] * 1e6 for p in pts], marker="o", label=f"{name} (p={slope:.2f})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("model size nv (tree velocity coordinates)")
    ax.set_ylabel("time per call (microseconds, median)")
    ax.set_title("cost vs model size, fitted t ~ nv^p", fontsize=9)
    return save_figure(fig, ax, folder, "bench_scale")


def markdown_report(results: list[MechanismBench], quick: bool, charts: list[Path], failures: list[str],
                    skipped: dict[str, str], fits) -> str:
    """docs/benchmarks.md: machine, goals, per-mechanism tables, scale fits, skipped mechanisms."""
    lines = ["# Benchmarks", "", "Generated by `mechkit bench" + (" --quick" if quick else "") +
             " --markdown docs/benchmarks.md` (do not edit by hand). Times are medians over repeats in one",
             "process on a shared machine: compare within a table, not across runs.", "", "## Machine", ""]
    lines += [f"- {k}: {v}" for k, v in machine().items()]
    lines += ["", "## Goals", "", goal_summary(results), ""] + [f"- {g}" for g in goals(results)]
    lines += ["", "## Peers and methods", "", PEER_NOTES, "## Columns", "",
              (f"error: per quantity, {'; '.join(f'{q}: {e}' for q, e in ERROR_LABELS.items())}. "
               f"x fastest: time / fastest method of equal or better accuracy (error within 10x, or both <= "
               f"{EQUAL_ACCURACY_FLOOR:g}; efforts-only rows are not counted against rows with reactions). x base: time / the baseline ({'; '.join(f'{q}: {m}' for q, m in BASELINES.items())})."),
              "", "## Results", ""]
    for b in results:
        lines.append(format_table(b, markdown=True))
    if fits:
        lines += ["## Scale", "", ("Time per call against nv (mechanisms timed round-robin), least-squares fit of "
                                   "log t = p log nv + c."), "",
                  "| method | p | points (mechanism nv: us) |", "|---|---|---|"]
        for name, pts, slope in fits:
            lines.append(f"| {name} | {slope:.2f} | " + ", ".join(f"{m} {n}: {t * 1e6:.1f}" for m, n, t in pts) + " |")
        lines.append("")
    if skipped:
        lines += ["## Not measured", ""] + [f"- {k}: {v}" for k, v in skipped.items()] + [""]
    if failures:
        lines += ["## Failure atlas", ""] + failures + [""]
    if charts:
        lines += ["## Charts", ""] + [f"![{p.stem}](figures/{p.name})" for p in charts if p.suffix == ".png"] + [""]
    return "\n".join(lines)


def run(names: Sequence[str] | None = None, quick: bool = True, with_peers: bool = True,
        progress: bool | None = None) -> tuple[list[MechanismBench], dict[str, str]]:
    """Bench the named mechanisms (default: every registered one); returns results and skipped ones."""
    from mechkit.registry import specs

    names = list(names or specs())
    results, skipped = [], {}
    for name in names:
        try:
            results.append(bench_mechanism(name, quick, with_peers, progress))
        except MechkitError as err:
            skipped[name] = str(err)
        except Exception as err:  # noqa: BLE001 - a broken mechanism module must not stop the others' bench: say what broke
            skipped[name] = f"{type(err).__name__}: {err}"
    return results, skipped


def bench_command(args) -> None:
    """`mechkit bench [names...] [--quick] [--charts DIR] [--markdown FILE]`: tables on stdout."""
    with np.errstate(under="ignore"):
        results, skipped = run(args.names, args.quick)
        for b in results:
            print(format_table(b))
        for line in goals(results):
            print(line)
        for name, why in skipped.items():
            print(f"{name}: not measured ({why})")
        fits = scale_fits(results)
        for name, pts, slope in fits:
            print(f"scale: {name}: t ~ nv^{slope:.2f} (" + ", ".join(f"{m} nv={n}: {t * 1e6:.1f} us" for m, n, t in pts) + ")")
        charts: list[Path] = []
        if args.charts:
            folder = Path(args.charts)
            with np.errstate(all="ignore"):  # matplotlib's own arithmetic
                for b in results:
                    for quantity in QUANTITIES:
                        charts += chart(b, quantity, folder)
                charts += scale_chart(fits, folder)
            print(f"wrote {len(charts)} charts to {folder}")
        if args.markdown:
            from mechkit.atomic import write_text

            failures = []
            if args.charts:
                from mechkit import failure_atlas

                failures = failure_atlas.summary_lines(Path(args.charts), quick=args.quick)
                charts = charts + sorted(Path(args.charts).glob("bench_atlas_*.png"))
            write_text(args.markdown, markdown_report(results, args.quick, charts, failures, skipped, fits))
            print(f"wrote {args.markdown}")
