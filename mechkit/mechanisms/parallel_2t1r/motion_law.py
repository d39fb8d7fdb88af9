"""The paper's motion law and the analytic motion states of the assembled branch along it.

theta_1 = pi t / 18, theta_2 = pi t / 15, theta_3 = pi t / 10 (rad), t in [0, 5] s; its start t = 0
is a parallel singularity (the five-bar's distal links collinear).
"""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.parallel_2t1r.assembly import assembled_pose
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams
from mechkit.mechanisms.parallel_2t1r.rates import State, motion_state

#: Motion law rates (rad/s): theta_1 = pi t/18, theta_2 = pi t/15, theta_3 = pi t/10, t in [0, 5] s.
MOTION_RATES = np.array([np.pi / 18.0, np.pi / 15.0, np.pi / 10.0])
MOTION_DURATION = 5.0


def motion_law(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Inputs theta_1..theta_3 (rad), rates (rad/s), accelerations (rad/s^2) of the paper's law at t (s)."""
    return MOTION_RATES * t, MOTION_RATES.copy(), np.zeros(3)


def state_at(p: Parallel2T1RParams, theta: np.ndarray, theta_dot: np.ndarray, theta_ddot: np.ndarray) -> State:
    """Full motion state of the assembled branch for the inputs, their rates and accelerations.

    Args:
        p: the parameters.
        theta: inputs theta_1..theta_3 (rad).
        theta_dot: their rates (rad/s).
        theta_ddot: their accelerations (rad/s^2).

    Raises:
        SingularConfiguration: J_p singular (e.g. the motion law's start, t = 0).
    """
    pose, theta4, _ = assembled_pose(p.dims, theta)
    return motion_state(p.dims, theta, theta_dot, theta_ddot, pose, theta4)


def motion_law_states(p: Parallel2T1RParams, times: np.ndarray) -> list[State]:
    """States along the motion law at ``times`` (s)."""
    return [state_at(p, *motion_law(float(t))) for t in times]
