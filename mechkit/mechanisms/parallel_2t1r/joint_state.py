"""The bridge from the paper's analytic state to the URDF's joint coordinates.

The URDF tree: base -> R_d1 -> link_d1 -> R_d2 -> link_d2 for the four limbs, platform on R23 at the
tip of link22; cuts R13 (link12/link22 at C1), R33 (link32/platform at C3), R43 (link42/platform at
C4). A tree joint's coordinate is its child's absolute angle about +y minus its parent's.
"""

from __future__ import annotations

import numpy as np

from mechkit.mechanism import Mechanism
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams
from mechkit.mechanisms.parallel_2t1r.rates import State, link_motion

#: Tree joints: (joint, child body, parent body or None for the base).
TREE = (
    ("R11", "link11", None),
    ("R12", "link12", "link11"),
    ("R21", "link21", None),
    ("R22", "link22", "link21"),
    ("R23", "platform", "link22"),
    ("R31", "link31", None),
    ("R32", "link32", "link31"),
    ("R41", "link41", None),
    ("R42", "link42", "link41"),
)


def joint_coordinates(p: Parallel2T1RParams, s: State) -> dict[str, tuple[float, float, float]]:
    """URDF tree joints -> (position rad, rate rad/s, acceleration rad/s^2) for an analytic state.

    Args:
        p: the parameters.
        s: an analytic state.

    Returns:
        Joint -> (position rad, rate rad/s, acceleration rad/s^2).
    """
    motion = link_motion(p.dims, s)
    out = {}
    for joint, child, parent in TREE:
        c = motion[child]
        if parent is None:  # R_d1: the paper's theta_d (link frame pitched by pi)
            ref_angle, ref_w, ref_e = np.pi, 0.0, 0.0
        else:
            ref = motion[parent]
            ref_angle, ref_w, ref_e = ref.angle, ref.omega[1], ref.alpha[1]
        q = float(np.angle(np.exp(1j * (c.angle - ref_angle))))
        out[joint] = (q, float(c.omega[1] - ref_w), float(c.alpha[1] - ref_e))
    return out


def joint_positions(p: Parallel2T1RParams, s: State) -> dict[str, float]:
    """URDF tree joints -> position (rad) of an analytic state: a closure-solve guess.

    Args:
        p: the parameters.
        s: an analytic state.

    Returns:
        Joint -> position (rad).
    """
    return {joint: c[0] for joint, c in joint_coordinates(p, s).items()}


def configuration(mech: Mechanism, s: State) -> np.ndarray:
    """The configuration q (nq,) of an analytic state: the neutral q with every tree joint set.

    Args:
        mech: the 2T1R.
        s: an analytic state.

    Returns:
        q (nq,).
    """
    q = mech.neutral()
    for joint, value in joint_positions(mech.params, s).items():
        q[mech.q_index(joint)] = value
    return q
