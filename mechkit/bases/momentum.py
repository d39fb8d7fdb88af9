"""The whole system's momentum along a motion: what a floating base with no gravity and no external force
conserves (the centre of mass then moves at p / M). The computation is the simulator's
(`mechkit.simulation.floating`, which records it along a floating run); this reads it for any mechanism
and motion, arguments checked.
"""

from __future__ import annotations

import numpy as np

from mechkit.base import arguments
from mechkit.base.exceptions import InvalidArgument
from mechkit.mechanism import Mechanism
from mechkit.simulation.floating import MomentumHistory, system_momentum

__all__ = ["MomentumHistory", "momentum"]


def momentum(mech: Mechanism, t: np.ndarray, q: np.ndarray, v: np.ndarray) -> MomentumHistory:
    """The whole system's momentum at each sample of a motion.

    Args:
        mech: the mechanism (any base; on a fixed one the ground's reactions change the momentum).
        t: (N,) times (s).
        q: (N, nq) configurations.
        v: (N, nv) joint velocities.

    Returns:
        The `MomentumHistory`.

    Raises:
        InvalidArgument: arrays of other shapes (one time and one velocity per configuration) or not finite.
    """
    q = arguments.array("q", q, mech.model.nq, batch=True).reshape(-1, mech.model.nq)
    v = arguments.array("v", v, mech.model.nv, batch=True).reshape(-1, mech.model.nv)
    t = arguments.array("t", t, len(q), batch=False)
    if len(v) != len(q):
        raise InvalidArgument("v", v.shape, f"expected one row per configuration ({len(q)})")
    return system_momentum(mech.model, t, q, v)
