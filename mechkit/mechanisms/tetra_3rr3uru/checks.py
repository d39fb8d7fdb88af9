"""The unit's `mechkit report` rows: the fold against eq. (6)-(8), and SOC against the constrained RNEA."""

from __future__ import annotations

import numpy as np

from mechkit.mechanism import Mechanism
from mechkit.mechanisms.tetra_3rr3uru import soc
from mechkit.mechanisms.truss.checks import CHECK_TIMES, fold_deviations
from mechkit.mechanisms.truss.fold import fold

SOC_REACTIONS = "SOC vs constrained RNEA, reactions (rel)"


def self_checks(mech: Mechanism, times: tuple[float, ...] = CHECK_TIMES) -> dict[str, float]:
    """Worst deviations along the fold at `times` (s): node positions against eq. (6)-(8) (m), closure
    residual, and the SOC reactions against the constrained RNEA (relative to the largest).

    Args:
        mech: the unit.
        times: instants of the fold, s.

    Returns:
        Check name -> worst deviation.
    """
    samples = fold(mech, np.asarray(times))
    worst = fold_deviations(mech, samples)
    worst[SOC_REACTIONS] = 0.0
    for sample in samples:
        reference = mech.inverse_dynamics(sample.q, sample.v, sample.a)
        result = soc.solve(mech, sample.t)
        scale = max(np.abs(r.wrench).max() for r in reference.reactions.values())
        error = max(np.abs(result.reactions[j] - r.wrench).max() for j, r in reference.reactions.items()) / scale
        worst[SOC_REACTIONS] = max(worst[SOC_REACTIONS], error)
    return worst
