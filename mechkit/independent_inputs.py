"""The joints whose values fix a mechanism's configuration: its actuators, completed where they are too few.

An under-actuated mechanism (the ten-bar's spring-loaded freedom) is not fixed by its actuators alone;
a study that drives it (a bench sample, the second opinion along a scene) also gives extra joints.
They are chosen in model order, each kept when it adds a freedom that the closure leaves free at the
home assembly (the velocity directions in the null space of the closure Jacobian).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from scipy.linalg import null_space

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism


def input_joints(mech: Mechanism) -> tuple[str, ...]:
    """The actuated joints, then (under-actuated mechanisms) extra joints completing a set of independent
    coordinates at the home assembly.

    Args:
        mech: the mechanism.

    Returns:
        Joint names: the actuated ones first, as many in all as the mechanism has DOF.
    """
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
