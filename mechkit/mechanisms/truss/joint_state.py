"""The paper's fold on the models' joints: the web-joint laws and the drive inputs (numpy only).

Shared by the unit `tetra_3rr3uru` and the composite `deployable_9rr12uru`: every web rod of a unit
turns at its two ends by combinations of the fold alpha and the tilt gamma of `truss.drives`.
"""

from __future__ import annotations

from mechkit.mechanisms.truss.drives import DriveState
from mechkit.mechanisms.truss.geometry import UNIT_NODES
from mechkit.mechanisms.truss.params import TetraParams


def web_joint_motion(p: TetraParams, s: DriveState, apexes: tuple[str, ...] = ("H",)) -> tuple[dict, dict, dict]:
    """Angles, rates, accelerations (rad, rad/s, rad/s^2) of every web-rod joint in the paper's motion s.

    Relative to the reference (alpha_ref, gamma_ref), per unit with apex X and nodes P, Q:
    rod AX at A turns by (gamma - gamma_ref) - (alpha - alpha_ref) (its absolute tilt), at X by
    alpha - alpha_ref (the fold drive); rods PX, QX turn by -(alpha - alpha_ref) at X and by
    (alpha - alpha_ref) - (gamma - gamma_ref) at P, Q (node attitude).

    Args:
        p: the unit's (or the composite's) parameters, for the reference configuration.
        s: the drive state at one instant.
        apexes: the units present ("H" for the unit; "H", "J", "I" for the composite).

    Returns:
        (joint -> angle (rad), joint -> rate (rad/s), joint -> acceleration (rad/s^2)).
    """
    da = (s.alpha - p.alpha_ref, s.alpha_rate, s.alpha_acc)
    dg = (s.gamma - p.gamma_ref, s.gamma_rate, s.gamma_acc)
    out: tuple[dict, dict, dict] = ({}, {}, {})
    for apex in apexes:
        x, b, e = UNIT_NODES[apex]
        for k in range(3):
            out[k].update(
                {
                    f"A{x}_A": dg[k] - da[k],
                    f"A{x}_{x}": da[k],
                    f"{b}{x}_{x}": -da[k],
                    f"{b}{x}_{b}": da[k] - dg[k],
                    f"{e}{x}_{x}": -da[k],
                    f"{e}{x}_{e}": da[k] - dg[k],
                }
            )
    return out


def drive_inputs(
    p: TetraParams, s: DriveState, actuated: tuple[str, ...], apexes: tuple[str, ...]
) -> tuple[dict, dict, dict]:
    """The paper's motion s on the actuated joints: (angles, rates, accelerations) by joint name.

    Args:
        p: the unit's (or the composite's) parameters.
        s: the drive state at one instant.
        actuated: the actuated joints.
        apexes: the units present.

    Returns:
        (joint -> angle (rad), joint -> rate, joint -> acceleration), the actuated joints only.
    """
    motion = web_joint_motion(p, s, apexes)
    return tuple({joint: values[joint] for joint in actuated} for values in motion)
