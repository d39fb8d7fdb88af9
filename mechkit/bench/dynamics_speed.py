"""Speed of the core's dynamics against one raw Pinocchio call and MuJoCo called bare (issues 13, 21, 33).

For one mechanism, every row is timed alternately with one raw `pin.constraintDynamics`, repeat after
repeat; each keeps its fastest repeat (the least disturbed on a shared machine) and the ratio is that
of the two minima. Rows: the forward-dynamics wrapper (proximal) and the exact null-space method; the
inverse dynamics with every reaction, one sample and batched (`BATCH` samples per call, time per
sample), determinacy off and on; velocities and accelerations; MuJoCo's `mj_forward` and `mj_inverse`
called bare on a state written once (warm start: each repeated call starts from the previous call's
`qacc_warmstart`, MuJoCo's best case; a cold row with `mjDSBL_WARMSTART`), and `mj_inverse` plus the
least-squares split of its constraint forces into efforts (`MujocoPeer.inverse`). The targets are
ratios of these rows; where one is missed, a breakdown times the steps of the call behind it in turn
with the whole call, so that they read as shares of it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MechkitError
from mechkit.bench.raw import raw_constraint_dynamics
from mechkit.bench.sampling import Sample, make_samples, rigid_mechanism
from mechkit.bench.timing import time_per_call
from mechkit.mechanism import Mechanism

#: Samples per batched call (the states of `make_samples`, tiled).
BATCH = 64
RAW = "raw pin.constraintDynamics (mu=1e-9)"
FORWARD = "forward_dynamics wrapper (proximal)"
EXACT = "forward_dynamics (nullspace, exact)"
ONE, ONE_DET = "inverse_dynamics, every reaction, determinacy off", "inverse_dynamics, every reaction, determinacy on"
BATCHED, BATCHED_DET = (
    f"batched inverse_dynamics (N={BATCH}), determinacy off",
    f"batched inverse_dynamics (N={BATCH}), determinacy on",
)
MJ_FORWARD, MJ_SPLIT = "MuJoCo mj_forward bare, warm start", "MuJoCo mj_inverse + split into efforts"
#: Issue 33's limits on one sample of inverse dynamics / raw, by mechanism (issue 21's on the truss).
ONE_SAMPLE_LIMITS = {"four_bar": 8.0, "parallel_2t1r": 5.0, "deployable_9rr12uru": 1.0}
#: The large model where the core's dynamics must match the peer: exact forward dynamics no slower than
#: MuJoCo's mj_forward, inverse dynamics per sample no slower than one raw constraintDynamics.
LARGE = "deployable_9rr12uru"


@dataclass(frozen=True)
class SpeedRow:
    """One timed call: microseconds per call (per sample for batched rows) and time / raw constraintDynamics."""

    label: str
    us: float
    ratio: float


@dataclass(frozen=True)
class SpeedTarget:
    """A target of issue 13, 21 or 33: `value` (a ratio) against `limit` (met when value <= limit)."""

    label: str
    value: float
    limit: float

    @property
    def met(self) -> bool:
        """Whether the target is met."""
        return bool(self.value <= self.limit)


@dataclass(frozen=True)
class Phase:
    """One step of a call: microseconds and its share of the whole call (timed alternately with it)."""

    call: str
    label: str
    us: float
    share: float


@dataclass(frozen=True)
class MechanismSpeed:
    """The rows of one mechanism (nv velocity coordinates), its targets and, where one is missed, the
    breakdown of the calls behind it."""

    name: str
    nv: int
    rows: list[SpeedRow]
    targets: list[SpeedTarget]
    phases: list[Phase] = field(default_factory=list)


def _calls(mech: Mechanism, samples: list[Sample]) -> dict[str, tuple[Callable[[Sample], object], int]]:
    """label -> (call on one sample, samples it handles)."""
    raw = raw_constraint_dynamics(mech)
    reps = -(-BATCH // len(samples))
    Q, V, A = (np.array([getattr(s, k) for s in samples] * reps)[:BATCH] for k in "qva")
    names = list(samples[0].input_names)
    R = np.array([s.rates for s in samples] * reps)[:BATCH]
    Acc = np.array([s.accelerations for s in samples] * reps)[:BATCH]
    calls = {
        RAW: (lambda s: raw(s.q, s.v, s.tau), 1),
        FORWARD: (lambda s: mech.forward_dynamics(s.q, s.v, s.tau), 1),
        EXACT: (lambda s: mech.forward_dynamics(s.q, s.v, s.tau, "nullspace"), 1),
        ONE: (lambda s: mech.inverse_dynamics(s.q, s.v, s.a, determinacy=False), 1),
        ONE_DET: (lambda s: mech.inverse_dynamics(s.q, s.v, s.a), 1),
        BATCHED: (lambda s: mech.inverse_dynamics_batch(Q, V, A, determinacy=False), BATCH),
        BATCHED_DET: (lambda s: mech.inverse_dynamics_batch(Q, V, A), BATCH),
        "velocities": (lambda s: mech.velocities(s.q, s.rates, names), 1),
        "accelerations": (lambda s: mech.accelerations(s.q, s.v, s.accelerations, names), 1),
        f"batched velocities (N={BATCH})": (lambda s: mech.velocities_batch(Q, R, names), BATCH),
        f"batched accelerations (N={BATCH})": (lambda s: mech.accelerations_batch(Q, V, Acc, names), BATCH),
    }
    calls.update(_mujoco_calls(mech, samples[0]))
    return calls


def _mujoco_calls(mech: Mechanism, s: Sample) -> dict[str, tuple[Callable[[Sample], object], int]]:
    """MuJoCo bare (state written once, warm and cold start) and mj_inverse + the split; {} without MuJoCo."""
    from mechkit.bench.peers import MujocoPeer

    try:
        warm, cold, split = MujocoPeer(mech), MujocoPeer(mech), MujocoPeer(mech)
    except MechkitError:
        return {}
    mj = warm._mj
    cold.model.opt.disableflags |= mj.mjtDisableBit.mjDSBL_WARMSTART
    for p in (warm, cold):
        p.set_state(s.q, s.v, s.tau)
        mj.mj_forward(p.model, p.data)
    inv = MujocoPeer(mech)
    inv.set_state(s.q, s.v, a=s.a)
    return {
        MJ_FORWARD: (lambda _: mj.mj_forward(warm.model, warm.data), 1),
        "MuJoCo mj_forward bare, cold start": (lambda _: mj.mj_forward(cold.model, cold.data), 1),
        "MuJoCo mj_inverse bare": (lambda _: mj.mj_inverse(inv.model, inv.data), 1),
        MJ_SPLIT: (lambda t: split.inverse(t.q, t.v, t.a), 1),
    }


def _interleaved(
    fn: Callable[[Sample], object], raw: Callable[[Sample], object], samples: list[Sample], budget: float, repeats: int
) -> tuple[float, float]:
    """Seconds per call of fn and of raw, timed alternately `repeats` times; the minimum of each (the
    least disturbed repeat on a shared machine)."""
    pairs = [
        (
            time_per_call(fn, samples, budget / repeats / 2, 1)[0],
            time_per_call(raw, samples, budget / repeats / 2, 1)[0],
        )
        for _ in range(repeats)
    ]
    return min(p[0] for p in pairs), min(p[1] for p in pairs)


def measure(mech: Mechanism, budget: float = 0.3, repeats: int = 15) -> MechanismSpeed:
    """Every row of one mechanism, each timed alternately with the raw call; then the targets and, where
    one is missed, the breakdown of the calls behind it (`phases`).

    Args:
        mech: the mechanism (measured without its springs: `rigid_mechanism`).
        budget: seconds of timing per row.
        repeats: timed repeats per row (the minimum is kept).

    Returns:
        The mechanism's rows (us per sample, ratio to the raw call), targets and breakdowns.
    """
    mech = rigid_mechanism(mech)
    samples = make_samples(mech, 3)
    calls = _calls(mech, samples)
    raw_fn = calls[RAW][0]
    raw_us = float(np.min(time_per_call(raw_fn, samples, budget, repeats))) * 1e6
    rows = [SpeedRow(RAW, raw_us, 1.0)]
    for label, (fn, per) in calls.items():
        if label == RAW:
            continue
        try:
            t, t_raw = _interleaved(fn, raw_fn, samples, budget, repeats)
        except MechkitError:
            continue  # e.g. a cut Pinocchio's constraintDynamics cannot express: no row
        rows.append(SpeedRow(label, t / per * 1e6, t / per / t_raw))
    found = targets(rows, mech.spec.name)
    missed = {t.label for t in found if not t.met}
    return MechanismSpeed(mech.spec.name, mech.model.nv, rows, found, phases(mech, samples, missed, budget, repeats))


def targets(rows: list[SpeedRow], name: str = "") -> list[SpeedTarget]:
    """The targets of issues 13, 21 and 33 on a mechanism's rows (those whose rows were measured).

    Args:
        rows: the mechanism's measured rows.
        name: the mechanism's name (some limits are per mechanism).

    Returns:
        One target per limit that applies, with its value and whether it is met.
    """
    r = {row.label: row.ratio for row in rows}
    out = []

    def add(label: str, num: str, den: str | None, limit: float | None) -> None:
        if limit is not None and num in r and (den is None or den in r):
            out.append(SpeedTarget(label, r[num] / (r[den] if den else 1.0), limit))

    add("one sample of inverse dynamics / raw", ONE, None, ONE_SAMPLE_LIMITS.get(name))
    add("batched inverse dynamics per sample / raw", BATCHED, None, 1.0 if name == LARGE else 1.5)
    add("forward_dynamics wrapper / raw", FORWARD, None, 2.0)
    add("inverse dynamics with determinacy / raw", ONE_DET, None, 2.0 if name == LARGE else None)
    add("exact forward dynamics / MuJoCo mj_forward", EXACT, MJ_FORWARD, 1.0 if name == LARGE else None)
    add("batched per sample / (mj_inverse + split)", BATCHED, MJ_SPLIT, 1.0)
    add("determinacy on / off, one sample", ONE_DET, ONE, 1.5)
    add("determinacy on / off, batched", BATCHED_DET, BATCHED, 1.5)
    return out


def phases(
    mech: Mechanism, samples: list[Sample], missed: set[str], budget: float = 0.3, repeats: int = 15
) -> list[Phase]:
    """Where the time of the calls behind missed targets goes: the whole call, the same call in the core
    (its difference: the argument checks and dispatch), the steps that can be called alone (Pinocchio's
    passes, the closure kernel, the reactions, the J a + gamma check; the core's remainder is the solve and
    the glue between steps), and MuJoCo's mj_forward beside the exact forward dynamics; all timed in turn
    on one state (`_round_robin`), each step's share its minimum over the whole call's.

    Args:
        mech: the mechanism.
        samples: the bench's states (the first is timed).
        missed: the labels of the missed targets (a call behind one is broken down).
        budget: seconds of timing per call.
        repeats: rounds of timing (the minimum is kept).

    Returns:
        The steps of each broken-down call, us and share of the call.
    """
    from mechkit import core

    cm, cd = mech.closure_model, mech.closure_model.create_data()
    model, data, k = cm.model, cd.pin, cm.kernel
    s = samples[0]
    q, v, a, tau = s.q, s.v, s.a, s.tau
    calls: dict[str, tuple[tuple[str, Callable], Callable | None, list[tuple[str, Callable]]]] = {}

    def core_id(det: bool) -> Callable:
        idle, rank = bool(mech.idle), mech.independent_rows  # the arguments Mechanism.inverse_dynamics passes
        return lambda _: core.inverse_dynamics(cm, cd, q, v, a, determinacy_test=det, generic_rank=rank, idle=idle)

    if "one sample of inverse dynamics / raw" in missed:
        lam = mech.inverse_dynamics(q, v, a, determinacy=False).multipliers
        world = k.world(cd.used_placements())
        _, _, W = k.rows(world, cd.J, q)
        origins, points = cd.oMi[1:, :, 3].copy(), k.points(world).copy()
        calls[ONE] = (
            ("Mechanism.inverse_dynamics", lambda _: mech.inverse_dynamics(q, v, a, determinacy=False)),
            core_id(False),
            [
                (
                    "Pinocchio: computeJointJacobians + rnea",
                    lambda _: (pin.computeJointJacobians(model, data, q), pin.rnea(model, data, q, v, a)),
                ),
                (
                    "closure rows: placements read, world vectors, rows",
                    lambda _: k.rows(k.world(cd.used_placements()), cd.J, q),
                ),
                (
                    "reactions: tree wrenches to world axes, the multipliers' loads",
                    lambda _: (core.tree_wrenches(cd.oMi, cd.f), k.joint_loads(W, lam, origins, points)),
                ),
            ],
        )
    if "determinacy on / off, one sample" in missed:
        whole = ("Mechanism.inverse_dynamics", lambda _: mech.inverse_dynamics(q, v, a))
        calls[ONE_DET] = (whole, core_id(True), [("determinacy off (the rest: the test's cost)", core_id(False))])
    if "forward_dynamics wrapper / raw" in missed:
        raw = raw_constraint_dynamics(mech)
        legacy = core.LegacyConstraints(model, list(mech.cuts), len(k.couplings))
        legacy.dynamics(q, v, tau, core.proximal_settings(1e-12, 1e-9, 20))  # the state the Jacobian is timed at
        calls[FORWARD] = (
            ("Mechanism.forward_dynamics", lambda _: mech.forward_dynamics(q, v, tau)),
            lambda _: core.forward_dynamics(cm, cd, q, v, tau),
            [  # the rest: the J a + gamma check (J a, math.dist and hypot), results, glue
                ("Pinocchio: constraintDynamics (the raw call)", lambda _: raw(q, v, tau)),
                ("Pinocchio: the anchors' Jacobian at the state (getConstraintsJacobian)", lambda _: legacy.jacobian()),
            ],
        )
    if "exact forward dynamics / MuJoCo mj_forward" in missed:

        def rows_and_drift(_: Sample) -> np.ndarray:
            G = cd.used_placements()
            world = k.world(G)
            _, _, W = k.rows(world, cd.J, q)
            return k.drift(G, k.twists(cd.J, v), k.twists(cd.dJ, v), q, v, world, W)

        pin.computeJointJacobiansTimeVariation(model, data, q, v)
        calls[EXACT] = (
            ("Mechanism.forward_dynamics, nullspace", lambda _: mech.forward_dynamics(q, v, tau, "nullspace")),
            lambda _: core.forward_dynamics(cm, cd, q, v, tau, "nullspace"),
            [
                (
                    "Pinocchio: computeJointJacobiansTimeVariation + crba + nonLinearEffects",
                    lambda _: (
                        pin.computeJointJacobiansTimeVariation(model, data, q, v),
                        pin.crba(model, data, q),
                        pin.nonLinearEffects(model, data, q, v),
                    ),
                ),
                ("closure rows and drift: placements read, world vectors, rows, twists, drift", rows_and_drift),
                *(
                    (f"(for comparison) {label}", fn)
                    for label, (fn, _) in _mujoco_calls(mech, s).items()
                    if label == MJ_FORWARD
                ),
            ],
        )
    out = []
    for call, ((label, whole), in_core, steps) in calls.items():
        t = _round_robin({"whole": whole, "core": in_core, **dict(steps)}, samples, budget, repeats)
        total, core_t = t["whole"], t["core"]
        named = sum(x for name, x in t.items() if name not in ("whole", "core") and not name.startswith("(for"))
        out += [
            Phase(call, f"whole call ({label})", total * 1e6, 1.0),
            Phase(
                call,
                "argument checks and dispatch (the whole call minus the core's)",
                max(total - core_t, 0.0) * 1e6,
                max(total - core_t, 0.0) / total,
            ),
        ]
        out += [Phase(call, name, x * 1e6, x / total) for name, x in t.items() if name not in ("whole", "core")]
        rest = max(core_t - named, 0.0)  # by difference: 0 where the steps' noise exceeds it
        what = "the determinacy test" if call == ONE_DET else "solve, certificates, results, glue"
        out.append(Phase(call, f"the rest of the core (by difference): {what}", rest * 1e6, rest / total))
    return out


def _round_robin(
    fns: dict[str, Callable[[Sample], object]], samples: list[Sample], budget: float, repeats: int
) -> dict[str, float]:
    """Seconds per call of each function, all timed in turn `repeats` times (so that a disturbance hits
    them alike); the minimum of each."""
    best = dict.fromkeys(fns, float("inf"))
    for _ in range(repeats):
        for name, fn in fns.items():
            best[name] = min(best[name], time_per_call(fn, samples, budget / repeats / len(fns), 1)[0])
    return best


def markdown(results: list[MechanismSpeed]) -> list[str]:
    """The benchmark page's section: one table of rows per mechanism, the targets, and the breakdowns.

    Args:
        results: what `measure` gave, one per mechanism.

    Returns:
        The section's markdown lines.
    """
    names = [r.name for r in results]
    labels = list(dict.fromkeys(row.label for r in results for row in r.rows))
    lines = [
        "| call | " + " | ".join(f"{n} (nv={r.nv})" for n, r in zip(names, results)) + " |",
        "|---|" + "---|" * len(results),
    ]
    for label in labels:
        cells = []
        for r in results:
            row = next((x for x in r.rows if x.label == label), None)
            cells.append(
                "-" if row is None else (f"{row.us:.1f} us" if label == RAW else f"{row.us:.1f} us ({row.ratio:.2f}x)")
            )
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    lines += ["", "| target | " + " | ".join(names) + " |", "|---|" + "---|" * len(results)]
    tlabels = list(dict.fromkeys(t.label for r in results for t in r.targets))
    for label in tlabels:
        cells = []
        for r in results:
            t = next((x for x in r.targets if x.label == label), None)
            cells.append("-" if t is None else f"{t.value:.2f} (<= {t.limit:g}: {'met' if t.met else 'MISSED'})")
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    for r in results:
        for call in dict.fromkeys(p.call for p in r.phases):
            lines += [
                "",
                f"Where the time of `{call}` goes on {r.name} (the steps timed in turn with the whole call):",
                "",
                "| step | us | share of the call |",
                "|---|---|---|",
            ]
            lines += [f"| {p.label} | {p.us:.1f} | {p.share:.0%} |" for p in r.phases if p.call == call]
    return lines
