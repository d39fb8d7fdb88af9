"""The methods the bench measures and the references it measures them against.

Methods: the core's, with their accuracy knobs swept (`core_methods`), and the mechanism's own,
declared on its spec (`MechanismSpec.bench_methods`, read by `own_methods`).

References (`references`): per quantity, the spec's own `BenchReference` when it declares one (for
four_bar and five_bar: the closed form and planar Newton-Euler, independent of Pinocchio);
otherwise the core's own tight solutions: closure Newton at 1e-13 for q (and the actuated inputs
read from it, for inverse kinematics), a from the closure kinematics with tau from the core's
inverse dynamics (so forward dynamics is checked against inverse dynamics), and the core inverse
dynamics itself.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from mechkit.base.exceptions import MechkitError
from mechkit.bench.errors import IDReference, id_parts
from mechkit.bench.raw import raw_constraint_dynamics
from mechkit.bench.sampling import Sample
from mechkit.catalog.contract import BENCH_QUANTITIES

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

#: Per quantity, the core's default method: the "x base" column divides by its time.
BASELINES = {
    "assembly": "closure Newton tol=1e-12",
    "forward_dynamics": "constraintDynamics mu=1e-09 it=20",
    "inverse_dynamics": "constrained RNEA + determinacy",
}


@dataclass(frozen=True)
class Method:
    """One way to compute a quantity.

    Attributes:
        name: label in tables and charts (unique per quantity).
        quantity: one of `mechkit.catalog.contract.BENCH_QUANTITIES`.
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
class References:
    """Per quantity: a label, and one reference value per sample (q (nq,), actuated inputs (na,), a (nv,),
    inverse dynamics)."""

    labels: dict[str, str]
    q: list[np.ndarray]
    inputs: list[np.ndarray]
    a: list[np.ndarray]
    inverse: list[IDReference]


def _core_inverse_reference(mech: Mechanism, s: Sample) -> IDReference:
    r = mech.inverse_dynamics(s.q, s.v, s.a, determinacy=True)
    return IDReference(
        dict(s.extra.get("efforts", r.efforts)),
        {k: x.wrench for k, x in r.reactions.items()},
        {k: x.determinate for k, x in r.reactions.items()},
    )


def references(mech: Mechanism, samples: list[Sample]) -> References:
    """The best reference per quantity (the spec's own, else the core's); sets each sample's tau to the
    reference efforts (unless the sample's efforts were drawn first).

    Args:
        mech: the mechanism.
        samples: the bench's states (their `tau` set here).

    Returns:
        The reference of every quantity at every sample, and their labels.
    """
    labels = {
        "assembly": "closure Newton at 1e-14 (or the tightest reached, core)",
        "forward_dynamics": "closure kinematics a, tau from the inverse-dynamics reference",
        "inverse_dynamics": "core constrained RNEA (determinacy on)",
    }
    core = [_core_inverse_reference(mech, s) for s in samples]
    if "efforts" in samples[0].extra:
        labels["forward_dynamics"] = "core exact null-space solve (under-actuated, or kinematic a inconsistent)"
        labels["inverse_dynamics"] = "the efforts that produced a (forward/inverse round trip); reactions: core"
    q_ref = [s.q.copy() for s in samples]
    a_ref = [s.a.copy() for s in samples]
    inverse = core
    spec = mech.spec
    if (own := spec.reference("assembly")) is not None:
        labels["assembly"] = own.label
        q_ref = [np.asarray(own.fn(mech, s), dtype=float) for s in samples]
    inputs_ref = [q[[mech.q_index(j) for j in mech.actuated]] for q in q_ref]
    if any(m.quantity == "inverse_kinematics" for m in spec.bench_methods):  # the core has no method of its own
        labels["inverse_kinematics"] = f"the actuated inputs of the assembly reference ({labels['assembly']})"
    if (own := spec.reference("inverse_kinematics")) is not None:
        labels["inverse_kinematics"] = own.label
        inputs_ref = [np.asarray(own.fn(mech, s), dtype=float) for s in samples]
    if (own := spec.reference("forward_dynamics")) is not None:
        labels["forward_dynamics"] = own.label
        a_ref = [np.asarray(own.fn(mech, s), dtype=float) for s in samples]
    if (own := spec.reference("inverse_dynamics")) is not None:
        labels["inverse_dynamics"] = own.label
        inverse = []
        for s, c in zip(samples, core):
            efforts, reactions = id_parts(own.fn(mech, s))
            reactions = reactions or {}
            inverse.append(
                IDReference(efforts, reactions, {k: c.determinate[k] for k in reactions if k in c.determinate})
            )
    for s, ref in zip(samples, inverse):
        if "efforts" not in s.extra:
            s.tau = mech.generalized_forces(ref.efforts)
    return References({q: labels[q] for q in BENCH_QUANTITIES if q in labels}, q_ref, inputs_ref, a_ref, inverse)


def core_methods(mech: Mechanism, quick: bool) -> list[Method]:
    """The core's methods with their accuracy knobs swept (fewer settings when quick).

    Args:
        mech: the mechanism.
        quick: fewer settings of each knob.

    Returns:
        The methods: closure Newton and LM at several tolerances, constraintDynamics at several mu and iteration
            counts, the dense KKT, constrained RNEA with and without the determinacy test, and the raw Pinocchio
            calls.
    """
    methods = []
    tols = (1e-6, 1e-12) if quick else (1e-4, 1e-6, 1e-9, 1e-12)
    for algo, label in (("newton", "closure Newton"), ("lm", "closure LM")):
        for tol in tols:
            methods.append(
                Method(
                    f"{label} tol={tol:g}",
                    "assembly",
                    lambda m, s, algo=algo, tol=tol: m.assemble(
                        dict(zip(s.input_names, s.inputs)), guess=s.extra["guess"], tol=tol, method=algo
                    ),
                    family=label,
                    knob=f"tol={tol:g}",
                )
            )
    mus = (1e-9, 1e-3) if quick else (1e-12, 1e-9, 1e-6, 1e-3)
    iters = (1, 20) if quick else (1, 3, 20)
    try:
        raw = raw_constraint_dynamics(mech)
    except MechkitError:
        raw = None
    if raw is not None:
        for it in iters:
            for mu in mus:
                methods.append(
                    Method(
                        f"constraintDynamics mu={mu:g} it={it}",
                        "forward_dynamics",
                        lambda m, s, mu=mu, it=it: (
                            m.forward_dynamics(s.q, s.v, s.tau, "proximal", mu=mu, max_iter=it).a
                        ),
                        family=f"constraintDynamics it={it}",
                        knob=f"mu={mu:g}",
                    )
                )
        methods.append(
            Method("raw pin.constraintDynamics (mu=1e-9)", "forward_dynamics", lambda m, s: raw(s.q, s.v, s.tau))
        )
    methods.append(
        Method(
            "dense KKT (independent rows)",
            "forward_dynamics",
            lambda m, s: m.forward_dynamics(s.q, s.v, s.tau, "kkt").a,
        )
    )
    methods.append(
        Method(
            "constrained RNEA + determinacy",
            "inverse_dynamics",
            lambda m, s: m.inverse_dynamics(s.q, s.v, s.a, determinacy=True),
        )
    )
    methods.append(
        Method(
            "constrained RNEA, no determinacy",
            "inverse_dynamics",
            lambda m, s: m.inverse_dynamics(s.q, s.v, s.a, determinacy=False),
        )
    )
    return methods


def own_methods(mech: Mechanism) -> list[Method]:
    """The mechanism's own methods, as its spec declares them (`MechanismSpec.bench_methods`).

    Args:
        mech: the mechanism.

    Returns:
        Its methods, in the spec's order.
    """
    return [Method(m.label, m.quantity, m.fn) for m in mech.spec.bench_methods]
