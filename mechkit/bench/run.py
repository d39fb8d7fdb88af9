"""Bench runs: every method on one mechanism (`bench_mechanism`), or on every registered one (`run`).

For a mechanism, the bench draws a few assembled states near home (`mechkit.bench.sampling`),
computes the best reference for each quantity and lists the methods (`mechkit.bench.methods`, the
peers of `mechkit.bench.peers`), then measures each method (`mechkit.bench.timing.measure`: its
error once, then microseconds per call), fills the ratio columns and times the goals' pairs back to
back. Progress goes to an optional callback; nothing here prints.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from mechkit.base.exceptions import MechkitError
from mechkit.bench.methods import BASELINES, core_methods, own_methods, references
from mechkit.bench.peers import peer_methods
from mechkit.bench.results import MechanismBench, Row
from mechkit.bench.sampling import Sample, make_samples, rigid_mechanism
from mechkit.bench.timing import measure, paired_ratio, ratios
from mechkit.catalog import registry
from mechkit.loading import load
from mechkit.mechanism import Mechanism

Progress = Callable[[str, int, int, str], None]
"""Called after each method is measured: (mechanism, methods done, methods in all, method's label)."""

#: The goals' pairs (numerator, denominator), timed back to back by `paired_ratio`.
GOAL_PAIRS = {
    "fd/mujoco": (BASELINES["forward_dynamics"], "MuJoCo mj_forward (default solref/solimp)"),
    "id/mujoco": ("constrained RNEA, no determinacy", "MuJoCo mj_forward (default solref/solimp)"),
    "id/raw": ("constrained RNEA, no determinacy", "raw pin.constraintDynamics (mu=1e-9)"),
    "id+det/raw": (BASELINES["inverse_dynamics"], "raw pin.constraintDynamics (mu=1e-9)"),
    "raw/mujoco": ("raw pin.constraintDynamics (mu=1e-9)", "MuJoCo mj_forward (default solref/solimp)"),
}


def _paired(mech: Mechanism, rows: list[Row], samples: list[Sample], budget: float, repeats: int) -> dict[str, float]:
    ok = {r.method.name: r.method for r in rows if r.outcome == "ok"}
    out = {}
    for key, (a, b) in GOAL_PAIRS.items():
        if a in ok and b in ok:
            out[key] = paired_ratio(
                lambda s, f=ok[a].run: f(mech, s), lambda s, f=ok[b].run: f(mech, s), samples, budget, repeats
            )
    return out


def bench_mechanism(
    mech: Mechanism, quick: bool = True, with_peers: bool = True, progress: Progress | None = None
) -> MechanismBench:
    """Every method on one mechanism, measured in this process: the core's, the spec's own, the peers'.

    Args:
        mech: the mechanism (measured without its springs: `rigid_mechanism`).
        quick: 3 samples, 2 settings per accuracy knob, 0.03 s of timing per method (else 8, all, 0.3 s).
        with_peers: also MuJoCo and Drake (where installed).
        progress: called after each method (see `Progress`).

    Returns:
        Its rows (one per method: error, time, outcome), samples, references and notes.
    """
    mech = rigid_mechanism(mech)
    name = mech.spec.name
    samples = make_samples(mech, 3 if quick else 8)
    refs = references(mech, samples)
    methods = core_methods(mech, quick) + own_methods(mech)
    notes: list[str] = []
    if with_peers:
        peer, notes = peer_methods(mech)
        methods += peer
    budget, repeats = (0.03, 5) if quick else (0.3, 15)
    rows = []
    for done, method in enumerate(methods, 1):
        rows.append(measure(mech, method, samples, refs, budget, repeats))
        if progress is not None:
            progress(name, done, len(methods), method.name)
    ratios(rows)
    paired = _paired(mech, rows, samples, budget * 4, max(repeats, 7))
    labels = dict(refs.labels)
    if notes:
        labels["peers"] = "; ".join(notes)
    return MechanismBench(name, mech.model.nv, mech.closure_model.kernel.size, labels, rows, paired, mech, samples)


def run(
    names: Sequence[str] | None = None, quick: bool = True, with_peers: bool = True, progress: Progress | None = None
) -> tuple[list[MechanismBench], dict[str, str]]:
    """Bench the named mechanisms; a mechanism that fails to load or to sample does not stop the others.

    Args:
        names: the mechanisms (default: every registered one).
        quick: as `bench_mechanism`.
        with_peers: as `bench_mechanism`.
        progress: as `bench_mechanism`.

    Returns:
        (the benches, mechanism -> why it was skipped).
    """
    results, skipped = [], {}
    for name in names or registry.names():
        try:
            results.append(bench_mechanism(load(name), quick, with_peers, progress))
        except MechkitError as err:
            skipped[name] = str(err)
        except Exception as err:  # noqa: BLE001 - a broken mechanism package must not stop the others' bench: say what broke
            skipped[name] = f"{type(err).__name__}: {err}"
    return results, skipped
