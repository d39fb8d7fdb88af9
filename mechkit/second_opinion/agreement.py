"""The second opinion against constrained RNEA (`Mechanism.inverse_dynamics`) over a scene's states.

States: poses spread along the mechanism's first declared scene (else the generic sweep,
`mechkit.scenes`), with input rates ~ N(0, 0.5) (the velocity moved to the nearest along which the
motion continues at second order, `Mechanism.second_order_velocity`) and input accelerations ~ N(0, 1)
(ours, seeded); an
under-actuated mechanism (or a pose where the closure kinematics cannot give a) gets random efforts on
its actuators and a from the core's dense KKT forward dynamics, as `mechkit.bench.sampling` does.

Agreement: every effort and every reaction component (world) that both methods call determinate,
relative to that quantity's largest magnitude over the states; a quantity smaller than
`NEGLIGIBLE` x the load level of its kind is measured against that floor instead (ours: such a
quantity, e.g. a pin's moment along its own axis, is zero up to rounding in both methods, and
rounding is relative to the loads the whole system carries). Load levels, over everything constrained
RNEA reports at the states (determinate or not): the largest effort; the largest force; for moments,
the larger of the largest moment and the largest force times the mechanism's extent
(`mechkit.scenes.joint_extent`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from mechkit.base.exceptions import MechkitError, MethodUnavailable
from mechkit.independent_inputs import input_joints
from mechkit.mechanism import Mechanism
from mechkit.scenes import joint_extent, scene_poses
from mechkit.second_opinion.opinion import SecondOpinion

#: Fraction of the largest quantity of a kind below which a quantity's own scale is not used.
NEGLIGIBLE = 1e-6

State = tuple[np.ndarray, np.ndarray, np.ndarray]


@dataclass
class Agreement:
    """Second opinion vs constrained RNEA over a scene.

    Attributes:
        samples: states compared.
        max_relative_difference: worst |SOC - RNEA| / scale over the compared quantities.
        worst: the quantity where it occurs ("effort R11", "reaction R43.fz").
        determinacy_mismatches: (joint.component, sample) where one method calls a component
            determinate and the other does not.
        us_per_sample: method -> microseconds per state (both give efforts, reactions, determinacy).
        consistency: worst relative residual of an SKC's equations (non-zero only where an SKC
            has more equations than unknowns).
        by_quantity: quantity -> its relative difference.
    """

    samples: int
    max_relative_difference: float
    worst: str
    determinacy_mismatches: list[str] = field(default_factory=list)
    us_per_sample: dict[str, float] = field(default_factory=dict)
    consistency: float = 0.0
    by_quantity: dict[str, float] = field(default_factory=dict)


def scene_states(mechanism: Mechanism, count: int, seed: int = 3, scene: str | None = None) -> list[State]:
    """Up to ``count`` moving states (q, v, a) along a scene (see the module docstring).

    Args:
        mechanism: the mechanism.
        count: how many states at most.
        seed: the random generator's seed (input rates and accelerations).
        scene: a scene name (`mechkit.scenes.scenes`); default: the first the spec declares, else the generic
            sweep.

    Returns:
        The states (q (nq,), v (nv,), a (nv,)).

    Raises:
        MethodUnavailable: no state could be built, or `count` < 1.
    """
    if count < 1:
        raise MethodUnavailable("second opinion samples", f"needs at least one sample, got {count}")
    scene = scene or next(iter(mechanism.spec.scenes), "sweep")
    poses = scene_poses(mechanism, scene)
    picks = np.unique(np.linspace(0, len(poses) - 1, min(count, len(poses))).round().astype(int))
    rng = np.random.default_rng(seed)
    names = input_joints(mechanism)
    out: list[State] = []
    why = ""
    used: set[int] = set()
    for pick in picks:
        for i in range(pick, len(poses)):  # a pose where the inputs do not fix the motion: the next one
            if i in used:
                continue
            used.add(i)
            try:
                out.append(_moving_state(mechanism, poses[i], names, rng))
                break
            except MechkitError as err:
                why = str(err)
    if not out:
        raise MethodUnavailable("second opinion samples", f"no moving state along {scene!r}: {why}")
    return out


def _moving_state(mechanism: Mechanism, q: np.ndarray, names: tuple[str, ...], rng: np.random.Generator) -> State:
    """(q, v, a) with random input rates and accelerations (or efforts; see the module docstring)."""
    act_v = [mechanism.v_index(j) for j in mechanism.actuated]
    v = mechanism.second_order_velocity(q, mechanism.velocities(q, rng.normal(0.0, 0.5, len(names)), inputs=names))
    accs = rng.normal(0.0, 1.0, len(names))
    a = None if len(names) > len(act_v) else mechanism.accelerations(q, v, accs, inputs=names)
    if a is None or np.abs(mechanism.closure_jacobian(q) @ a + mechanism.closure_drift(q, v)).max() > 1e-9:
        tau = np.zeros(mechanism.model.nv)
        tau[act_v] = rng.normal(0.0, 1.0, len(act_v))
        a = mechanism.forward_dynamics(q, v, tau, "kkt").a
    return q, v, a


def _us_per_state(fn, states: list[State], repeats: int = 3) -> float:
    """Best-of-``repeats`` microseconds per state of ``fn(q, v, a)``."""
    best = np.inf
    for _ in range(repeats):
        start = time.perf_counter()
        for q, v, a in states:
            fn(q, v, a)
        best = min(best, (time.perf_counter() - start) / len(states))
    return best * 1e6


def agreement(opinion: SecondOpinion, states: list[State], timing: bool = True) -> Agreement:
    """Compare the second opinion with constrained RNEA on ``states`` (see the module docstring).

    Args:
        opinion: the second opinion of a mechanism.
        states: states (q, v, a) of that mechanism.
        timing: also time both methods (best of three passes over the states; ``us_per_sample``).

    Returns:
        The largest relative difference and where, the determinacy mismatches, the SKCs' consistency, and the
            timings.
    """
    mech = opinion.mechanism
    ours = [opinion.solve(q, v, a) for q, v, a in states]
    theirs = [mech.inverse_dynamics(q, v, a) for q, v, a in states]
    values: dict[str, tuple[str, list[float], list[float]]] = {}
    mismatches = []
    for s, (mine, ref) in enumerate(zip(ours, theirs, strict=True)):
        for name, effort in ref.efforts.items():
            if ref.efforts_determinate[name] != (not mine.free_efforts[name]):
                mismatches.append(f"{name}.effort@{s}")
            elif ref.efforts_determinate[name]:
                values.setdefault(f"effort {name}", ("effort", [], []))[1].append(mine.efforts[name])
                values[f"effort {name}"][2].append(effort)
        for name, reaction in ref.reactions.items():
            fixed = ~mine.free[name]
            for k, label in enumerate(("fx", "fy", "fz", "mx", "my", "mz")):
                if reaction.determinate[k] != fixed[k]:
                    mismatches.append(f"{name}.{label}@{s}")
                elif fixed[k]:
                    key = f"reaction {name}.{label}"
                    values.setdefault(key, ("force" if k < 3 else "moment", [], []))[1].append(mine.reactions[name][k])
                    values[key][2].append(reaction.wrench[k])
    largest = {
        "effort": max(max(np.abs(list(r.efforts.values())), default=0.0) for r in theirs),
        "force": max(max(np.abs(x.wrench[:3]).max() for x in r.reactions.values()) for r in theirs),
        "moment": max(max(np.abs(x.wrench[3:]).max() for x in r.reactions.values()) for r in theirs),
    }
    extent = joint_extent(mech.model, mech.model.createData(), states[0][0])
    largest["moment"] = max(largest["moment"], largest["force"] * extent)
    by_quantity = {}
    for key, (kind, mine, ref) in values.items():
        scale = max(float(np.max(np.abs(ref))), NEGLIGIBLE * largest[kind], 1e-300)
        by_quantity[key] = float(np.max(np.abs(np.subtract(mine, ref))) / scale)
    label = max(by_quantity, key=by_quantity.__getitem__, default="")
    times = {}
    if timing:
        times = {
            "second opinion (SOC virtual work)": _us_per_state(opinion.solve, states),
            "constrained RNEA + determinacy": _us_per_state(mech.inverse_dynamics, states),
        }
    consistency = max(max(o.consistency.values(), default=0.0) for o in ours)
    return Agreement(len(states), by_quantity.get(label, 0.0), label, mismatches, times, consistency, by_quantity)
