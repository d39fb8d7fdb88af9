"""The unit's own methods in `mechkit bench` (`SPEC.bench_methods`, `SPEC.bench_references`), on the
states along the paper's fold (`truss.bench.fold_states`).

Assembly: the fold's continuation step (`truss.bench.FOLD_STEP`). Inverse dynamics: SOC virtual work
of the unit (`soc.solve`, numpy, motion from the paper's node positions and drive laws at the
sample's time), also the independent reference.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from mechkit.base.exceptions import MethodUnavailable
from mechkit.catalog.contract import BenchMethod, BenchReference
from mechkit.mechanisms.tetra_3rr3uru import soc
from mechkit.mechanisms.truss.bench import FOLD_STEP
from mechkit.validation.soc import SOCResult

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = ["METHODS", "REFERENCES"]


def soc_along_the_fold(mech: Mechanism, sample: Any) -> SOCResult:
    """SOC inverse dynamics of the unit at the sample's time along the fold.

    Args:
        mech: the unit.
        sample: a bench sample along the fold (its time in `extra["t"]`).

    Returns:
        Efforts and every joint's reaction.

    Raises:
        MethodUnavailable: the sample is not a state along the fold (no time).
    """
    if "t" not in sample.extra:
        raise MethodUnavailable("SOC of the unit", "needs a state along the fold (its time)")
    return soc.solve(mech, sample.extra["t"])


METHODS = (
    FOLD_STEP,
    BenchMethod(
        "SOC virtual work of the unit (numpy, the paper's fold motion)", "inverse_dynamics", soc_along_the_fold
    ),
)
REFERENCES = (
    BenchReference(
        "SOC virtual work of the unit (numpy, the paper's fold motion)", "inverse_dynamics", soc_along_the_fold
    ),
)
