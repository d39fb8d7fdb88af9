"""Speed of the core's dynamics against one raw Pinocchio call and MuJoCo called bare (issue 13).

For one mechanism, every row is timed alternately with one raw `pin.constraintDynamics`, repeat after
repeat; each keeps its fastest repeat (the least disturbed on a shared machine) and the ratio is
that of the two minima.
Rows: the forward-dynamics wrapper; the inverse dynamics with every reaction, one sample and batched
(`BATCH` samples per call, time per sample), determinacy off and on; velocities and accelerations;
MuJoCo's `mj_forward` and `mj_inverse` called bare on a state written once (warm start: each
repeated call starts from the previous call's `qacc_warmstart`, MuJoCo's best case; a cold row with
`mjDSBL_WARMSTART`), and `mj_inverse` plus the least-squares split of its constraint forces into
efforts (`MujocoPeer.inverse`). Each target of issue 13 is a ratio checked on these rows.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import MechkitError
from mechkit.bench.raw import raw_constraint_dynamics
from mechkit.bench.sampling import Sample, make_samples
from mechkit.bench.timing import time_per_call
from mechkit.mechanism import Mechanism

#: Samples per batched call (the states of `make_samples`, tiled).
BATCH = 64
RAW = "raw pin.constraintDynamics (mu=1e-9)"


@dataclass(frozen=True)
class SpeedRow:
    """One timed call: microseconds per call (per sample for batched rows) and time / raw constraintDynamics."""

    label: str
    us: float
    ratio: float


@dataclass(frozen=True)
class SpeedTarget:
    """A target of issue 13: `value` (a ratio) against `limit` (met when value <= limit)."""

    label: str
    value: float
    limit: float

    @property
    def met(self) -> bool:
        """Whether the target is met."""
        return bool(self.value <= self.limit)


@dataclass(frozen=True)
class MechanismSpeed:
    """The rows of one mechanism (nv velocity coordinates) and its targets."""

    name: str
    nv: int
    rows: list[SpeedRow]
    targets: list[SpeedTarget]


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
        "forward_dynamics wrapper (proximal)": (lambda s: mech.forward_dynamics(s.q, s.v, s.tau), 1),
        "inverse_dynamics, every reaction, determinacy off": (
            lambda s: mech.inverse_dynamics(s.q, s.v, s.a, determinacy=False), 1),
        "inverse_dynamics, every reaction, determinacy on": (lambda s: mech.inverse_dynamics(s.q, s.v, s.a), 1),
        f"batched inverse_dynamics (N={BATCH}), determinacy off": (
            lambda s: mech.inverse_dynamics_batch(Q, V, A, determinacy=False), BATCH),
        f"batched inverse_dynamics (N={BATCH}), determinacy on": (lambda s: mech.inverse_dynamics_batch(Q, V, A), BATCH),
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
        "MuJoCo mj_forward bare, warm start": (lambda _: mj.mj_forward(warm.model, warm.data), 1),
        "MuJoCo mj_forward bare, cold start": (lambda _: mj.mj_forward(cold.model, cold.data), 1),
        "MuJoCo mj_inverse bare": (lambda _: mj.mj_inverse(inv.model, inv.data), 1),
        "MuJoCo mj_inverse + split into efforts": (lambda t: split.inverse(t.q, t.v, t.a), 1),
    }


def _interleaved(fn: Callable[[Sample], object], raw: Callable[[Sample], object], samples: list[Sample],
                 budget: float, repeats: int) -> tuple[float, float]:
    """Seconds per call of fn and of raw, timed alternately `repeats` times; the minimum of each (the
    least disturbed repeat on a shared machine)."""
    pairs = [(time_per_call(fn, samples, budget / repeats / 2, 1)[0], time_per_call(raw, samples, budget / repeats / 2, 1)[0])
             for _ in range(repeats)]
    return min(p[0] for p in pairs), min(p[1] for p in pairs)


def measure(mech: Mechanism, budget: float = 0.3, repeats: int = 15) -> MechanismSpeed:
    """Every row of one mechanism, each timed alternately with the raw call; then the targets of issue 13."""
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
    return MechanismSpeed(mech.spec.name, mech.model.nv, rows, targets(rows))


def targets(rows: list[SpeedRow]) -> list[SpeedTarget]:
    """Issue 13's targets on a mechanism's rows (those whose rows were measured)."""
    r = {row.label: row.ratio for row in rows}
    out = []

    def add(label: str, num: str, den: str | None, limit: float) -> None:
        if num in r and (den is None or den in r):
            out.append(SpeedTarget(label, r[num] / (r[den] if den else 1.0), limit))

    one, one_det = ("inverse_dynamics, every reaction, determinacy off", "inverse_dynamics, every reaction, determinacy on")
    batch, batch_det = (f"batched inverse_dynamics (N={BATCH}), determinacy off",
                        f"batched inverse_dynamics (N={BATCH}), determinacy on")
    add("one sample of inverse dynamics / raw", one, None, 10.0)
    add("batched inverse dynamics per sample / raw", batch, None, 5.0)
    add("batched per sample / (mj_inverse + split)", batch, "MuJoCo mj_inverse + split into efforts", 1.0)
    add("determinacy on / off, one sample", one_det, one, 1.5)
    add("determinacy on / off, batched", batch_det, batch, 1.5)
    add("forward_dynamics wrapper / raw", "forward_dynamics wrapper (proximal)", None, 1.5)
    return out


def markdown(results: list[MechanismSpeed]) -> list[str]:
    """The benchmark page's section: one table of rows per mechanism, then the targets."""
    names = [r.name for r in results]
    labels = list(dict.fromkeys(row.label for r in results for row in r.rows))
    lines = ["| call | " + " | ".join(f"{n} (nv={r.nv})" for n, r in zip(names, results)) + " |",
             "|---|" + "---|" * len(results)]
    for label in labels:
        cells = []
        for r in results:
            row = next((x for x in r.rows if x.label == label), None)
            cells.append("-" if row is None else (f"{row.us:.1f} us" if label == RAW else f"{row.us:.1f} us ({row.ratio:.2f}x)"))
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    lines += ["", "| target | " + " | ".join(names) + " |", "|---|" + "---|" * len(results)]
    tlabels = list(dict.fromkeys(t.label for r in results for t in r.targets))
    for label in tlabels:
        cells = []
        for r in results:
            t = next((x for x in r.targets if x.label == label), None)
            cells.append("-" if t is None else f"{t.value:.2f} (<= {t.limit:g}: {'met' if t.met else 'MISSED'})")
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    return lines
