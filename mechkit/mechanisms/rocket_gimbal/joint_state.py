"""The engine gimbal's Pinocchio tree filled from the analytic motion (no closure solve), and read back.

Tree joints, as in the xacro: bracket_hinge (alpha), engine_hinge (beta), and per servo "a" / "b" the
Hooke angles *_swing_1, *_swing_2 (t1, t2 of `rocket_gimbal.body_motion`) and the stroke *_stroke = L - l0;
the ball joints at the engine pivots are the loop cuts.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mechkit.mechanisms.rocket_gimbal.body_motion import GimbalMotion

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = ["hinges", "joint_state"]


def hinges(mech: Mechanism, x: np.ndarray, index: str = "v") -> np.ndarray:
    """(alpha, beta) entries of a joint vector: q with index="q" (rad), v or a with "v" (rad/s, rad/s^2).

    Args:
        mech: the gimbal.
        x: a joint vector: q (nq,), or v or a (nv,).
        index: "q" for a configuration, "v" for a velocity or acceleration.

    Returns:
        (alpha, beta) entries (2,).
    """
    pick = mech.q_index if index == "q" else mech.v_index
    return np.array([x[pick("bracket_hinge")], x[pick("engine_hinge")]])


def joint_state(mech: Mechanism, motion: GimbalMotion) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(q, v, a) of the URDF tree from the analytic motion (no closure solve).

    Args:
        mech: the gimbal.
        motion: the analytic motion.

    Returns:
        (q (nq,), v (nv,), a (nv,)).
    """
    p = mech.params
    values = {
        "bracket_hinge": (motion.angles[0], motion.rates[0], motion.accs[0]),
        "engine_hinge": (motion.angles[1], motion.rates[1], motion.accs[1]),
    }
    for name, leg, l0 in zip("ab", motion.legs, (p.length_a, p.length_b)):
        for i in range(2):
            values[f"{name}_swing_{i + 1}"] = (leg.hooke[i], leg.hooke_rate[i], leg.hooke_acc[i])
        values[f"{name}_stroke"] = (leg.length - l0, leg.length_rate, leg.length_acc)
    q, v, a = mech.neutral(), np.zeros(mech.model.nv), np.zeros(mech.model.nv)
    for joint, (x, xd, xdd) in values.items():
        q[mech.q_index(joint)], v[mech.v_index(joint)], a[mech.v_index(joint)] = x, xd, xdd
    return q, v, a
