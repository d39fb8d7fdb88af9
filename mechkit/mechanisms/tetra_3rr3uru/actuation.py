"""The unit's actuated joints and its home inputs."""

from __future__ import annotations

from mechkit.mechanisms.truss.params import TetraParams

#: Actuated joints of the unit: fold at H (paper), attitude at B (paper), and rod EH at H in place of
#: the paper's attitude drive at E: in this model the attitudes of B and E are tied to first order
#: at every configuration of the paper's motion (mirror symmetric), so B and E together cannot be
#: inputs (the passive block of the closure Jacobian is singular).
ACTUATED = ("AH_H", "BH_B", "EH_H")


def home(p: TetraParams) -> dict[str, float]:
    """Zero on every drive (rad): the reference configuration, the paper's t = 0 of the fold.

    Args:
        p: the unit's parameters.

    Returns:
        Drive -> 0.0.
    """
    return {joint: 0.0 for joint in ACTUATED}
