"""The engine gimbal as a design: the figure of merit a sweep asks of it (`SPEC.design_metrics`).

`rule_error` (rad): the linear rule's worst error (|exact - rule| over both angles) over the stroke
square +-`RULE_STROKE`, on a `RULE_GRID` x `RULE_GRID` grid (the 45 x 45 grid of the linearisation
study gives the same worst value at the default geometry, 9.021e-3 rad).
"""

from __future__ import annotations

from mechkit.catalog.contract import DesignMetric
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.rocket_gimbal.kinematics import linear_rule_errors
from mechkit.mechanisms.rocket_gimbal.params import geometry

#: Grid points per stroke axis of the sweep's rule error (odd: the grid holds the null pose).
RULE_GRID = 15


def rule_error(mech: Mechanism) -> dict[str, float]:
    """The linear rule's worst error over the stroke square at the design's geometry.

    Args:
        mech: the gimbal (one design).

    Returns:
        {"rule_error": the worst error, rad}.
    """
    return {"rule_error": linear_rule_errors(geometry(mech.params), n=RULE_GRID).worst}


DESIGN_METRICS = (
    DesignMetric(
        "rule_error", "rad", "the linear rule's worst error over the stroke square", ("rule_error",), rule_error
    ),
)
