"""Checks of a truss model along the paper's fold (rows of `mechkit report`)."""

from __future__ import annotations

import numpy as np

from mechkit.mechanism import Mechanism
from mechkit.mechanisms.truss.drives import drive_state
from mechkit.mechanisms.truss.fold import FoldSample, fold
from mechkit.mechanisms.truss.nodes import node_positions

#: Instants of the fold sampled by `fold_checks`, s.
CHECK_TIMES = (0.0, 100.0, 200.0)

POSITIONS = "fold: node positions vs eq. (6)-(8) (m)"
RESIDUAL = "fold: closure residual"


def fold_deviations(mech: Mechanism, samples: list[FoldSample]) -> dict[str, float]:
    """Worst deviations over fold samples: node positions against eq. (6)-(8) (m), closure residual.

    Args:
        mech: `tetra_3rr3uru` or `deployable_9rr12uru`.
        samples: fold samples.

    Returns:
        Check name -> worst deviation.
    """
    g = mech.params.geometry()
    worst = {POSITIONS: 0.0, RESIDUAL: 0.0}
    for sample in samples:
        s = drive_state(sample.t)
        expected = g.node_positions(s.alpha, s.gamma)
        error = max(np.abs(p - expected[n]).max() for n, p in node_positions(mech, sample.q).items())
        worst[POSITIONS] = max(worst[POSITIONS], error)
        worst[RESIDUAL] = max(worst[RESIDUAL], np.abs(mech.closure_residual(sample.q)).max())
    return worst


def fold_checks(mech: Mechanism, times: tuple[float, ...] = CHECK_TIMES) -> dict[str, float]:
    """`fold_deviations` along the fold at `times` (s): the composite's `mechkit report` rows.

    Args:
        mech: `tetra_3rr3uru` or `deployable_9rr12uru`.
        times: instants of the fold, s.

    Returns:
        Check name -> worst deviation.
    """
    return fold_deviations(mech, fold(mech, np.asarray(times)))
