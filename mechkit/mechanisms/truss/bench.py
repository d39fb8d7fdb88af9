"""What the truss mechanisms give `mechkit bench`: states along the paper's fold and its continuation step.

`fold_states` (`MechanismSpec.bench_states` of `tetra_3rr3uru` and `deployable_9rr12uru`): the bench
measures on instants spread along the 200 s fold, each with the state 1 s before it, with the fold's
own velocities and accelerations (the drive laws projected through the closure). `FOLD_STEP`: the
fold's own assembly method, one continuation step from the state before (predictor q + v dt, Newton
on the passive joints), what the fold scene does at every step.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from mechkit.base.exceptions import MethodUnavailable
from mechkit.catalog.contract import BenchMethod, MotionState
from mechkit.mechanisms.truss.drives import FOLD_DURATION
from mechkit.mechanisms.truss.fold import fold, fold_step

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

#: Time (s) between a bench state and the state before it (the fold scene's step).
LEAD = 1.0
#: Closure residual (m / dimensionless) of the continuation step, as the fold's.
TOL = 1e-12


def fold_states(mech: Mechanism, count: int) -> list[MotionState]:
    """`count` instants spread over the fold (the last at its end), each preceded by the state `LEAD` s
    before it: 2 `count` states in time order.

    Args:
        mech: `tetra_3rr3uru` or `deployable_9rr12uru`.
        count: how many instants.

    Returns:
        The states (t, q, v, a) in time order.
    """
    ends = np.linspace(FOLD_DURATION / count, FOLD_DURATION, count)
    times = np.ravel(np.column_stack([ends - LEAD, ends]))
    return [MotionState(s.t, s.q, s.v, s.a) for s in fold(mech, times)]


def continuation_step(mech: Mechanism, sample: Any) -> np.ndarray:
    """Assembly by one fold step from the state before the sample (`fold.fold_step`).

    Args:
        mech: `tetra_3rr3uru` or `deployable_9rr12uru`.
        sample: a bench sample along the fold (`extra["t"]`, `extra["previous"]`).

    Returns:
        q (nq,) at the sample's time.

    Raises:
        MethodUnavailable: the sample is not a state along the fold (no time, no state before it).
    """
    previous = sample.extra.get("previous")
    if previous is None:
        raise MethodUnavailable("fold step", "needs a state along the fold (`fold_states`) and the one before it")
    return fold_step(mech, previous.q, previous.v, previous.t, sample.extra["t"], TOL).q


FOLD_STEP = BenchMethod(
    f"fold step: predictor q + v dt, Newton on the passive joints ({LEAD:g} s)", "assembly", continuation_step
)
