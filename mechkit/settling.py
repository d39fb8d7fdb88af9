"""Holding at rest: the configuration where the motions no actuator drives carry no load.

The actuators hold their joints (`held_joints`) at given values; what they do not drive (joints on
springs, rods spinning about their own axes: `undriven_motions`) settles where the load on it,
gravity minus the springs (`rest_load`, the gradient of `potential_energy`), vanishes (`settle`).
`outside_range` names a joint that settled beyond the range its file declares. `mechkit.report`
holds the mechanism there.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pinocchio as pin
import scipy.linalg

from mechkit import core
from mechkit.base.exceptions import ClosureNotConverged, MechkitError
from mechkit.mechanism import Mechanism

#: Largest load left along the motions no actuator drives at a settled configuration, relative to the
#: largest generalised load (absolute below 1 N m): a tenth of what the inverse dynamics accepts as held
#: there (1e-9), so that the efforts are not refused for it; above the rounding of that load at a closed
#: configuration (1e-12 on Gepetto's five-bar, whose end spheres weigh 654 t; ours).
SETTLE_TOL = 1e-10
#: Newton steps `settle` takes before it gives up (ours: the field's robots settle in under ten).
SETTLE_STEPS = 50
#: Central-difference step of the settling Hessian (rad or m along unit motions; ours).
SETTLE_STEP = 1e-6
#: A joint whose value changed by more than this (rad or m) while settling is listed as settled (ours:
#: above the closure's own scatter, 1e-12).
SETTLED = 1e-9


def held_joints(m: Mechanism) -> tuple[str, ...]:
    """The joints the actuators act on, held still at rest: a motor's joint, each joint of a tendon.

    Args:
        m: the mechanism.

    Returns:
        The joint names, each once, in actuator order.
    """
    tendons = {a.name: a for a in m.closure_model.actuators}
    joints = [j for name in m.actuated for j in ([j for j, _ in tendons[name].joints] if name in tendons else [name])]
    return tuple(dict.fromkeys(joints))


def undriven_motions(m: Mechanism, q: np.ndarray, held: Sequence[str]) -> np.ndarray:
    """The motions at q that close every loop and move no `held` joint.

    Args:
        m: the mechanism.
        q: (nq,) a closed configuration.
        held: the joints kept still (`held_joints`).

    Returns:
        (nv, d) an orthonormal basis of those motions (rank judged as the core judges it,
        `mechkit.core.RANK_TOL`).
    """
    select = np.zeros((len(held), m.model.nv))
    for k, joint in enumerate(held):
        select[k, m.v_index(joint)] = 1.0
    return scipy.linalg.null_space(np.vstack([m.closure_jacobian(q), select]), rcond=core.RANK_TOL)


def rest_load(m: Mechanism, q: np.ndarray) -> np.ndarray:
    """The generalised force the joints must supply to hold q at rest: gravity minus the springs.

    Args:
        m: the mechanism.
        q: (nq,) the configuration.

    Returns:
        (nv,) the load (N m or N), the gradient of `potential_energy`.
    """
    g = pin.computeGeneralizedGravity(m.model, m.data, q).copy()
    passive = m.passive_forces(q, np.zeros(m.model.nv))
    return g if passive is None else g - passive


def potential_energy(m: Mechanism, q: np.ndarray) -> float:
    """The potential energy of gravity and the joint springs at q.

    Args:
        m: the mechanism.
        q: (nq,) the configuration.

    Returns:
        The energy (J).
    """
    gravity = float(pin.computePotentialEnergy(m.model, m.data, q))
    return gravity + (float(m.springs.potential(q)) if m.springs else 0.0)


def settle(m: Mechanism, q: np.ndarray) -> np.ndarray:
    """The configuration near q (nq,) where the motions no actuator drives carry no load: the actuators'
    joints held at their values in q, every loop closed, the potential energy (gravity and springs) at a
    minimum along the undriven motions (`undriven_motions`: joints on springs, rods spinning about their
    own axes).

    Newton on the load along those motions, U^T (g - f_springs), its Hessian by central differences of
    `SETTLE_STEP` along them (made positive definite, so that each step lowers the energy), steps shortened
    until the energy falls, each configuration closed again (`Mechanism.solve_closure`), until that load
    is below `SETTLE_TOL` of the largest generalised load. q itself when no undriven motion is loaded.

    Args:
        m: the mechanism.
        q: (nq,) a closed configuration, the start.

    Returns:
        (nq,) the settled configuration.

    Raises:
        MechkitError: the undriven motions do not settle within `SETTLE_STEPS` steps (a load nothing
            balances, e.g. a passive slide under gravity), naming the joints they move.
        ClosureNotConverged: a loop does not close along the way.
    """
    held = held_joints(m)

    def along(U: np.ndarray, q: np.ndarray) -> np.ndarray:  # U^T P(q) load(q), P the projector on q's undriven motions
        here = undriven_motions(m, q, held)
        return U.T @ (here @ (here.T @ rest_load(m, q)))

    def moved(q: np.ndarray, step: np.ndarray) -> np.ndarray:
        return m.solve_closure(pin.integrate(m.model, q, step), held).q

    with np.errstate(under="ignore"):
        for _ in range(SETTLE_STEPS):
            U = undriven_motions(m, q, held)
            load = rest_load(m, q)
            G = U.T @ load
            scale = max(1.0, float(np.max(np.abs(load))))
            if U.shape[1] == 0 or np.max(np.abs(G)) <= SETTLE_TOL * scale:
                return q
            H = np.column_stack(
                [
                    (along(U, moved(q, SETTLE_STEP * u)) - along(U, moved(q, -SETTLE_STEP * u))) / (2 * SETTLE_STEP)
                    for u in U.T
                ]
            )
            w, V = np.linalg.eigh(0.5 * (H + H.T))
            w = np.maximum(np.abs(w), 1e-9 * max(float(np.max(np.abs(w))), scale))
            dz = -V @ ((V.T @ G) / w)
            before, t = potential_energy(m, q), 1.0
            while t > 1e-9:
                try:
                    trial = moved(q, t * (U @ dz))
                except ClosureNotConverged:
                    t *= 0.5
                    continue
                if potential_energy(m, trial) <= before or np.max(np.abs(along(U, trial))) < np.max(np.abs(G)):
                    q = trial
                    break
                t *= 0.5
            else:
                break
    joints = [
        m.model.names[j]
        for j in range(1, m.model.njoints)
        if np.max(np.abs(U[m.model.joints[j].idx_v : m.model.joints[j].idx_v + m.model.nvs[j]]), initial=0.0) > 0.1
    ]
    raise MechkitError(
        f"the motions no actuator drives do not settle: after {SETTLE_STEPS} steps they still carry "
        f"{np.max(np.abs(G)):.3e} (N m or N) of load, moving {', '.join(joints)}"
    )


def outside_range(m: Mechanism, q: np.ndarray, start: np.ndarray) -> str:
    """The first one-freedom joint that moved from `start` to q and lies at q outside its declared range.

    The range is the model's position limits, where lower < upper (a URDF joint without bounds has 0, 0);
    outside means by more than `SETTLED`.

    Args:
        m: the mechanism.
        q: (nq,) the configuration reached.
        start: (nq,) the configuration it started from.

    Returns:
        That joint, its value and range (rad or m) in words; "" when there is none.
    """
    model = m.model
    for j in range(1, model.njoints):
        if model.nqs[j] != 1:
            continue
        i = model.joints[j].idx_q
        low, high = model.lowerPositionLimit[i], model.upperPositionLimit[i]
        if low < high and abs(q[i] - start[i]) > SETTLED and not low - SETTLED <= q[i] <= high + SETTLED:
            return f"{model.names[j]} at {q[i]:.6g}, outside its range [{low:.6g}, {high:.6g}]"
    return ""
