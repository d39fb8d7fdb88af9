"""Inverse dynamics with joint friction from the reactions: the efforts a motion needs when the joints rub.

The reactions give the friction (`mechkit.forces.ReactionFriction`), the friction changes the efforts
and the reactions: starting without friction, the core's inverse dynamics is solved again with the
friction of the last reactions as passive forces (tree joints) and body moments (cut joints) until
no friction torque changes by more than `FRICTION_TOL` of the largest. Then it is checked: the core's
forward dynamics under the efforts found, the friction and the other elements must give back the
motion's accelerations. Where the iteration does not settle, friction locks the mechanism
(`FrictionLocks`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechkit import core
from mechkit.base.exceptions import ConstraintViolated
from mechkit.forces import ForceElement, ForceState, FrictionLocks, generalized_of_wrenches
from mechkit.simulation.prescribed import Drives
from mechkit.simulation.system import FRICTION_ITERATIONS, FRICTION_TOL, MechanismSystem

#: Largest |a(FD of the efforts found) - a| relative to max |a| (and 1 rad/s^2) the check accepts (ours).
CHECK_TOL = 1e-8


@dataclass(frozen=True)
class FrictionInverse:
    """Inverse dynamics with friction at one state.

    Attributes:
        result: the core's result at the fixed point (efforts of the actuators, every reaction).
        friction: joint -> the friction torque's size T (N m) at the fixed point, per friction element.
        generalized: (nv,) the elements' generalised forces (friction included; N m or N).
        wrenches: (njoints, 6) the elements' body wrenches (`fext` convention).
        iterations: fixed-point iterations.
        check: the forward-dynamics check's largest acceleration difference (rad/s^2 or m/s^2).
    """

    result: core.InverseDynamicsResult
    friction: dict[str, float]
    generalized: np.ndarray
    wrenches: np.ndarray
    iterations: int
    check: float


def inverse_dynamics(
    mech: Any, q: np.ndarray, v: np.ndarray, a: np.ndarray, elements: list[ForceElement], t: float = 0.0
) -> FrictionInverse:
    """The actuators' efforts and every reaction for one state of a motion under force elements, friction
    from the reactions included (see the module docstring).

    Args:
        mech: the mechanism (`mechkit.Mechanism`); its actuators give the efforts.
        q: (nq,) configuration closing the loops.
        v: (nv,) velocities satisfying the closures.
        a: (nv,) accelerations satisfying the closures (J a + gamma = 0).
        elements: the force elements (the mechanism's springs are not added: pass `mech.springs`).
        t: the time (s) for elements that depend on it.

    Returns:
        The `FrictionInverse`: the core's result at the fixed point, the friction torques, the elements'
        loads, the iterations and the forward-dynamics check.

    Raises:
        InvalidParameters: a mechanism without actuators.
        FrictionLocks: the fixed point does not settle.
        ConstraintViolated: the forward-dynamics check fails.
    """
    mech.require_actuators("inverse dynamics with friction")
    held = Drives(held={j: 0.0 for j in mech.actuated})  # the actuated joints as the drives: their motors' efforts
    system = MechanismSystem(mech, elements, held, "kkt")
    state = ForceState.at(system.model, system.data, q, v, t)
    plain = [k for k in range(len(elements)) if k not in system.friction]
    tau_p, fext_p, _ = system._loads(state, plain)
    tau_f, fext_f = np.zeros_like(tau_p), np.zeros_like(fext_p)
    iterations = 0
    while True:
        out = system.reactions(q, v, a, tau_p + tau_f, fext_p + fext_f)
        if not system.friction:
            break
        state.reactions = out.reaction_values
        new_tau, new_fext, _ = system._loads(state, system.friction)
        change = max(
            float(np.max(np.abs(new_tau - tau_f), initial=0.0)), float(np.max(np.abs(new_fext - fext_f), initial=0.0))
        )
        scale = max(float(np.max(np.abs(new_tau), initial=0.0)), float(np.max(np.abs(new_fext), initial=0.0)), 1e-300)
        tau_f, fext_f = new_tau, new_fext
        iterations += 1
        if change <= FRICTION_TOL * scale or change == 0.0:
            out = system.reactions(q, v, a, tau_p + tau_f, fext_p + fext_f)
            state.reactions = out.reaction_values
            break
        if iterations >= FRICTION_ITERATIONS:
            raise FrictionLocks(change, FRICTION_TOL * scale, iterations)
    generalized, wrenches = tau_p + tau_f, fext_p + fext_f
    tau = (
        mech.closure_model.actuation.T @ out.effort_values
        + generalized
        + generalized_of_wrenches(system.model, state.data, wrenches)
    )
    a_check = core.forward_dynamics(system.cm, system.cd, q, v, tau, "kkt").a
    check = float(np.max(np.abs(a_check - a)))
    limit = CHECK_TOL * max(float(np.max(np.abs(a))), 1.0)
    if not check <= limit:
        raise ConstraintViolated(check, limit, "inverse dynamics with friction: the forward dynamics of its efforts")
    friction = {}
    for k in system.friction:
        friction.update(elements[k].torques(state))
    return FrictionInverse(out, friction, generalized, wrenches, iterations, check)
