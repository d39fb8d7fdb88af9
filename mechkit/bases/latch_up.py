"""The latch-up shock: the impulse each joint carries when a joint latches (`mechkit.simulation.Latch`).

A latch stops a joint at once: the velocities jump from v- to v+ on the closed mechanism. The impulse
every joint carries is the constrained inverse dynamics of that jump, read as impulses: with the
velocities at rest, RNEA(q, 0, dv) - RNEA(q, 0, 0) = M dv, solved for the drives' impulses and every
joint's reaction impulse (N s, N m s; world axes, about the joint origin), the latched joint and the
prescribed inputs among the driven joints. Carnot's theorem gives the energy the jump took,
1/2 dv^T M dv, beside the simulator's figure.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.base.exceptions import InvalidArgument
from mechkit.mechanism import Mechanism
from mechkit.motion.study import driven_model


@dataclass(frozen=True)
class LatchUp:
    """The latch-up's impulses.

    Attributes:
        driven: driven joint -> its impulse (N m s or N s): the latch's and the drives'.
        reactions: joint -> (6,) reaction impulse [f (N s), m (N m s)], world axes, about the joint origin.
        energy: J, 1/2 dv^T M dv (Carnot: the kinetic energy the plastic jump took).
    """

    driven: dict[str, float]
    reactions: dict[str, np.ndarray]
    energy: float


def latch_up(
    mech: Mechanism, q: np.ndarray, v_before: np.ndarray, v_after: np.ndarray, driven: Sequence[str]
) -> LatchUp:
    """The impulses of a velocity jump at a latch.

    Args:
        mech: the mechanism.
        q: (nq,) the configuration at the latch.
        v_before: (nv,) velocities just before (J v = 0).
        v_after: (nv,) just after (J v = 0, the latched joint and the drives at their rates).
        driven: the joints whose impulses are unknowns: the latched joint and the prescribed inputs (with
            them the motion is determined).

    Returns:
        The `LatchUp`.

    Raises:
        InvalidArgument: velocities of the wrong size, or a jump that leaves the closures.
        SingularConfiguration: the driven joints do not determine the motion.
    """
    dv = np.asarray(v_after, dtype=float) - np.asarray(v_before, dtype=float)
    if dv.shape != (mech.model.nv,) or not np.all(np.isfinite(dv)):
        raise InvalidArgument("v_before/v_after", dv.shape, f"expected two finite ({mech.model.nv},) velocities")
    J = mech.closure_jacobian(q)
    if np.abs(J @ dv).max(initial=0.0) > 1e-8 * max(np.abs(dv).max(), 1e-12):
        raise InvalidArgument("v_before/v_after", "J dv != 0", "the jump must keep the closures")
    cm = driven_model(mech, list(driven))
    rest = np.zeros(mech.model.nv)
    jumped, still = (core.inverse_dynamics(cm, cm.create_data(), q, rest, a) for a in (dv, rest))
    names = list(jumped.joint_names)
    reactions = {j: jumped.reaction_values[k] - still.reaction_values[k] for k, j in enumerate(names)}
    efforts = dict(zip(cm.actuated, jumped.effort_values - still.effort_values))
    M = pin.crba(mech.model, mech.model.createData(), q)
    M = np.triu(M) + np.triu(M, 1).T
    return LatchUp({j: float(x) for j, x in efforts.items()}, reactions, 0.5 * float(dv @ M @ dv))
