"""Pinocchio's own constrained dynamics called bare: the reference every speed ratio divides by."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from mechkit import core

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

#: Pinocchio's proximal settings of the raw call (accuracy, mu, max_iter): mu = 1e-9 as the bench has always timed.
RAW_SETTINGS = (1e-12, 1e-9, 20)


def raw_constraint_dynamics(mech: Mechanism) -> Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]:
    """A function (q, v, tau) -> a that is one bare `pin.constraintDynamics` call on the mechanism's
    legacy constraint models (set up once, `RAW_SETTINGS`; the result is Pinocchio's own array).

    Args:
        mech: the mechanism.

    Returns:
        The function, (q (nq,), v (nv,), tau (nv,)) -> a (nv,).

    Raises:
        MethodUnavailable: a cut or coupling the legacy constraint models cannot express.
    """
    legacy = core.LegacyConstraints(mech.model, list(mech.cuts), len(mech.closure_model.kernel.couplings))
    prox = core.proximal_settings(*RAW_SETTINGS)
    bare, model, data, cms, cds = core.raw_constraint_dynamics, mech.model, legacy.data, legacy.models, legacy.datas
    return lambda q, v, tau: bare(model, data, q, v, tau, cms, cds, prox)
