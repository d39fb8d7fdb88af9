"""The bench's mechanism and states: the rigid mechanism, and assembled configurations near home with
random input rates and accelerations.

Every method of a mechanism is measured on the same few `Sample`s, drawn by `make_samples`, of the
mechanism `rigid_mechanism` gives: without its joint springs and dampers, so that its efforts are the
actuators' alone, as the references, the raw Pinocchio call and the peers (their springs disabled) take them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MechkitError, MethodUnavailable
from mechkit.catalog.contract import MotionState
from mechkit.independent_inputs import input_joints

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism


def rigid_mechanism(mech: Mechanism) -> Mechanism:
    """The mechanism the bench measures: the same, without its joint springs and dampers.

    Args:
        mech: the mechanism.

    Returns:
        `mech` itself when it has no spring, else a mechanism of the same closure model without them.
    """
    if not mech.springs:
        return mech
    return type(mech)(mech.spec, mech.params, mech.closure_model, mech.urdf)


#: Largest offset of the sampled inputs from the home inputs (rad or m).
INPUT_SPREAD = 0.05


@dataclass
class Sample:
    """One assembled state of a mechanism (SI units, mechkit's joint vectors).

    `inputs`, `rates`, `accelerations` are values of `input_names`: the actuated joints, then extra
    joints when the actuators alone do not fix the configuration (under-actuated mechanisms).
    `q`, `v`, `a`, `tau` are (nq,), (nv,), (nv,), (nv,) joint vectors; `extra` caches data of the
    methods (and holds "guess", the configuration the assembly methods start from, "efforts" when
    the efforts were drawn first and a follows from the dynamics, and, for a state along the
    mechanism's own motion (`MechanismSpec.bench_states`), "t" (s) and "previous", the
    `MotionState` before it).
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


def scene_configurations(mech: Mechanism, count: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """Up to `count` (configuration, the scene's previous configuration) pairs spread along the first
    scene the mechanism's spec declares; the previous one is the assembly's warm start.

    Args:
        mech: the mechanism.
        count: how many pairs at most.

    Returns:
        The pairs, none when the spec declares no scene.
    """
    for scene in mech.spec.scenes.values():
        poses = [np.asarray(q, dtype=float) for q in scene(mech)]
        picks = np.linspace(1, len(poses) - 1, min(count, len(poses) - 1)).round().astype(int)
        return [(poses[i], poses[i - 1]) for i in picks]
    return []


def _closes(mech: Mechanism, q: np.ndarray, v: np.ndarray, a: np.ndarray) -> bool:
    """Whether a satisfies the acceleration-level closure J a + gamma = 0 to 1e-9 (relative)."""
    J = mech.closure_jacobian(q)
    gamma = mech.closure_drift(q, v)
    return bool(
        np.max(np.abs(J @ a + gamma), initial=0.0)
        <= 1e-9 * max(np.max(np.abs(J), initial=0.0) * np.max(np.abs(a)), np.max(np.abs(gamma), initial=0.0), 1e-12)
    )


def motion_states(mech: Mechanism, count: int) -> list[tuple[MotionState, MotionState]]:
    """Up to `count` (state, the state before it) pairs spread along the mechanism's own motion
    (`MechanismSpec.bench_states`), or none when its spec declares no such motion.

    Args:
        mech: the mechanism.
        count: how many pairs at most.

    Returns:
        The pairs of `MotionState`s.
    """
    if mech.spec.bench_states is None:
        return []
    states = list(mech.spec.bench_states(mech, count))
    picks = np.linspace(1, len(states) - 1, min(count, len(states) - 1)).round().astype(int)
    return [(states[i], states[i - 1]) for i in picks]


def make_samples(mech: Mechanism, count: int, seed: int = 7) -> list[Sample]:
    """`count` assembled states near home (closure tolerance 1e-12), or along the mechanism's own motion.

    Where the spec declares its own motion (`MechanismSpec.bench_states`): states along it, with its
    velocities and accelerations. Else inputs within INPUT_SPREAD of home (divided by 5 until the
    linkage assembles), then, if too few assemble, configurations along the spec's first scene;
    input rates ~ N(0, 0.5), the velocity then moved to the nearest one along which the motion continues
    at second order (`Mechanism.second_order_velocity`: at a redundant configuration, such as the
    deployable's, a velocity in the null space of J may move along a freedom that exists only
    instantaneously, where no acceleration closes the loops).
    Fully actuated: input accelerations ~ N(0, 1) and a from the closure kinematics (tau is set by
    `mechkit.bench.methods.references`). Under-actuated, or where that a does not satisfy
    J a + gamma = 0 to 1e-9 (a rank change near home): efforts ~ N(0, generalised gravity scale) on
    the actuators and a from the core's exact null-space forward dynamics (the inverse dynamics must give
    those efforts back).

    Args:
        mech: the mechanism.
        count: how many states.
        seed: the random generator's seed.

    Returns:
        The samples, `count` of them.

    Raises:
        MethodUnavailable: no state could be assembled.
    """
    rng = np.random.default_rng(seed)
    names = input_joints(mech)
    under = len(names) > len(mech.actuated)
    act_v = [mech.v_index(j) for j in mech.actuated]
    home = np.array([mech.home_q[mech.q_index(j)] for j in names])
    out: list[Sample] = []
    why = ""
    data = mech.model.createData()

    def add(
        q: np.ndarray, guess: np.ndarray, state: MotionState | None = None, previous: MotionState | None = None
    ) -> None:
        """Moving state at q: the motion's own rates (`state`), else random input rates; accelerations
        the motion's or from the closure, else from the dynamics. `guess` is where the assembly
        methods start from."""
        inputs = np.array([q[mech.q_index(j)] for j in names])
        if state is None:
            rates = rng.normal(0.0, 0.5, home.size)
            accs = rng.normal(0.0, 1.0, home.size)
            v = mech.second_order_velocity(q, mech.velocities(q, rates, inputs=names))  # along a finite motion
            rates = np.concatenate([np.atleast_1d(v[mech.v_index(j)]) for j in names])
            a = None if under else mech.accelerations(q, v, accs, inputs=names)
        else:
            columns = [mech.v_index(j) for j in names]
            v, rates, accs = state.v, state.v[columns], state.a[columns]
            a = None if under else state.a
        tau = np.zeros(mech.model.nv)
        if a is not None and not _closes(mech, q, v, a):
            a = None  # the projection is inconsistent here (second-order mobility): use the dynamics
        if a is None:
            scale = max(float(np.max(np.abs(pin.computeGeneralizedGravity(mech.model, data, q)[act_v]))), 1e-3)
            tau[act_v] = rng.normal(0.0, scale, len(act_v))
            a = mech.forward_dynamics(q, v, tau, "nullspace").a
            accs = a[[mech.v_index(j) for j in names]]
        sample = Sample(inputs, rates, accs, q, v, a, tau, tuple(names))
        if tau.any():
            sample.extra["efforts"] = {j: float(tau[i]) for j, i in zip(mech.actuated, act_v)}
        sample.extra["guess"] = guess
        if state is not None:
            sample.extra["t"], sample.extra["previous"] = state.t, previous
        out.append(sample)

    declared = motion_states(mech, count)
    for state, previous in declared:
        try:
            add(state.q, previous.q, state, previous)
        except MechkitError as err:
            why = str(err)
    for spread in (INPUT_SPREAD, INPUT_SPREAD / 5, INPUT_SPREAD / 25):
        for _ in range(count * 2):
            if len(out) == count or declared:
                break
            try:
                q = mech.assemble(dict(zip(names, home + rng.uniform(-spread, spread, home.size))), guess=mech.home_q)
                add(q, mech.home_q)
            except MechkitError as err:
                why = str(err)
    if len(out) < count and not declared:
        # some linkages do not assemble for arbitrary inputs near home (a freedom that exists only
        # along the mechanism's own motion): take states along its first scene instead
        for q, previous in scene_configurations(mech, count - len(out)):
            try:
                add(q, previous)
            except MechkitError as err:
                why = str(err)
    if not out:
        raise MethodUnavailable("bench samples", f"no state of {mech.spec.name} to measure on: {why}")
    return out
