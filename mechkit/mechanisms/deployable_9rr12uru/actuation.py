"""The composite's actuated joints and its home inputs."""

from __future__ import annotations

from mechkit.mechanisms.deployable_9rr12uru.params import DeployableParams

#: Fold at H, J, I and attitude at B, F, G as in the paper; rod EH at H in place of the attitude drive
#: at E (B and E attitudes are tied to first order in this model, see `tetra_3rr3uru.actuation`).
ACTUATED = ("AH_H", "AJ_J", "AI_I", "BH_B", "FJ_F", "GI_G", "EH_H")


def home(p: DeployableParams) -> dict[str, float]:
    """Zero on every drive (rad): the reference configuration, the paper's t = 0 of the fold.

    Args:
        p: the composite's parameters.

    Returns:
        Drive -> 0.0.
    """
    return {joint: 0.0 for joint in ACTUATED}
