"""Error measures of the bench, one per quantity, against the reference of each sample.

- "assembly": max |q - q_ref| (rad or m, angle differences wrapped).
- "inverse_kinematics": max |x - x_ref| over the actuated inputs (rad or m, wrapped as for assembly).
- "forward_dynamics": max |a - a_ref| / max |a_ref|.
- "inverse_dynamics": max |x - x_ref| / max |x_ref| over efforts and the reaction components that
  static equilibrium determines (the core's determinacy flags); moments of actuated joints are left
  out (they hold the effort, compared as such). A result with efforts only is compared on efforts
  ("efforts only").
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

ERROR_LABELS = {
    "assembly": "max |q - q_ref| (rad or m)",
    "inverse_kinematics": "max |inputs - inputs_ref| (rad or m)",
    "forward_dynamics": "max |a - a_ref| / max |a_ref| (-)",
    "inverse_dynamics": "max relative error of efforts and determinate reactions (-)",
}


@dataclass
class IDReference:
    """Reference inverse dynamics at one sample.

    Attributes:
        efforts: actuated joint -> effort (N m or N).
        reactions: joint -> (6,) world wrench [f, m] parent on child at the joint origin (N, N m).
        determinate: joint -> (6,) bool, the components static equilibrium determines.
    """

    efforts: dict[str, float]
    reactions: dict[str, np.ndarray]
    determinate: dict[str, np.ndarray]


def _wrap(x: np.ndarray) -> np.ndarray:
    return (x + np.pi) % (2.0 * np.pi) - np.pi


def assembly_error(q: np.ndarray, q_ref: np.ndarray) -> float:
    """max |q - q_ref| with angle differences wrapped to (-pi, pi] (rad or m); also the inverse-kinematics
    error, on the actuated inputs.

    Args:
        q: a configuration (or the actuated inputs).
        q_ref: the reference, of the same shape.

    Returns:
        The largest difference (rad or m).
    """
    return float(np.max(np.abs(_wrap(np.asarray(q) - q_ref))))


def acceleration_error(a: np.ndarray, a_ref: np.ndarray) -> float:
    """max |a - a_ref| / max |a_ref| (a_ref scale floored at 1e-300).

    Args:
        a: accelerations (nv,).
        a_ref: the reference accelerations (nv,).

    Returns:
        The relative error (-).

    Raises:
        FloatingPointError: a is not finite.
    """
    a = np.asarray(a, dtype=float)
    if not np.all(np.isfinite(a)):
        raise FloatingPointError("non-finite accelerations")
    return float(np.max(np.abs(a - a_ref)) / max(np.max(np.abs(a_ref)), 1e-300))


def id_parts(result: Any) -> tuple[dict[str, float], dict[str, np.ndarray] | None]:
    """Efforts and (if given) reactions as (6,) wrenches of an inverse-dynamics result (object or dict).

    Args:
        result: an inverse-dynamics result: an object or a dict with `efforts` and optionally `reactions`
            (`JointReaction`s or (6,) wrenches).

    Returns:
        (actuated joint -> effort (N m or N), joint -> (6,) world wrench [f, m], or None when the result has no
            reactions).

    Raises:
        TypeError: the result has no `efforts`.
    """
    get = result.get if isinstance(result, dict) else (lambda k, d=None: getattr(result, k, d))
    efforts = get("efforts")
    reactions = get("reactions", None)
    if efforts is None:
        raise TypeError("an inverse-dynamics result needs 'efforts'")
    if reactions is not None:
        reactions = {k: np.asarray(getattr(r, "wrench", r), dtype=float) for k, r in reactions.items()}
    return dict(efforts), reactions


def inverse_error(result: Any, ref: IDReference, actuated: Sequence[str]) -> tuple[float, str]:
    """Relative error of efforts and determinate reaction components, and a note ("efforts only", ...).

    Args:
        result: an inverse-dynamics result (see `id_parts`).
        ref: the reference efforts, reactions and their determinacy.
        actuated: the actuated joints (their reaction moments are efforts, not compared).

    Returns:
        (largest difference of an effort or a determinate reaction component relative to the reference's largest
            magnitude (-), a note: "efforts only" when the result has no reactions, "k/n reactions" when it has
            some of them, else "").
    """
    efforts, reactions = id_parts(result)
    scale = max(
        [abs(u) for u in ref.efforts.values()] + [float(np.max(np.abs(w))) for w in ref.reactions.values()] + [1e-300]
    )
    worst = max(abs(efforts[j] - u) for j, u in ref.efforts.items())
    if reactions is None:
        return worst / scale, "efforts only"
    compared = 0
    for joint, wrench in ref.reactions.items():
        if joint not in reactions:
            continue
        mask = ref.determinate[joint].copy()
        if joint in actuated:
            mask[3:] = False
        if mask.any():
            worst = max(worst, float(np.max(np.abs(reactions[joint][mask] - wrench[mask]))))
            compared += 1
    note = "" if compared == len(ref.reactions) else f"{compared}/{len(ref.reactions)} reactions"
    return worst / scale, note
