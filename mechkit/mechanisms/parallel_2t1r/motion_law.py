"""The paper's motion law and the analytic motion states of the assembled branch along it.

theta_1 = pi t / 18, theta_2 = pi t / 15, theta_3 = pi t / 10 (rad), t in [0, 5] s; its start t = 0
is a parallel singularity (the five-bar's distal links collinear).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mechkit.catalog.contract import SampledLaw
from mechkit.mechanisms.parallel_2t1r.branch import INPUTS, assembled_pose
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams
from mechkit.mechanisms.parallel_2t1r.rates import State, motion_state

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

#: Motion law rates (rad/s): theta_1 = pi t/18, theta_2 = pi t/15, theta_3 = pi t/10, t in [0, 5] s.
MOTION_RATES = np.array([np.pi / 18.0, np.pi / 15.0, np.pi / 10.0])
MOTION_DURATION = 5.0
#: Samples of the motion law in (0, 5] s (the issue's 501: t = 0 is a parallel singularity).
LAW_SAMPLES = 501


def motion_law(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Inputs theta_1..theta_3 (rad), rates (rad/s), accelerations (rad/s^2) of the paper's law at t (s).

    Args:
        t: time, s.

    Returns:
        (theta (3,), rates (3,), accelerations (3,)).
    """
    return MOTION_RATES * t, MOTION_RATES.copy(), np.zeros(3)


def motion_law_times(samples: int = LAW_SAMPLES) -> np.ndarray:
    """`samples` uniform times (s) in (0, `MOTION_DURATION`]: the law without its singular start.

    Args:
        samples: how many times.

    Returns:
        (samples,) times, s.
    """
    return np.linspace(MOTION_DURATION / samples, MOTION_DURATION, samples)


def sampled_motion_law(mech: Mechanism, samples: int | None = None) -> SampledLaw:
    """The paper's law on the three motors at `motion_law_times` (`SPEC.motion_laws["motion_law"]`).

    Args:
        mech: the 2T1R (the law does not depend on its parameters).
        samples: how many times (default `LAW_SAMPLES`).

    Returns:
        The law on R11, R21, R31.
    """
    t = motion_law_times(samples or LAW_SAMPLES)
    values, rates, accelerations = (np.array(x) for x in zip(*(motion_law(float(x)) for x in t)))
    return SampledLaw(INPUTS, t, values, rates, accelerations, source="motion law theta = pi t (1/18, 1/15, 1/10)")


def state_at(p: Parallel2T1RParams, theta: np.ndarray, theta_dot: np.ndarray, theta_ddot: np.ndarray) -> State:
    """Full motion state of the assembled branch for the inputs, their rates and accelerations.

    Args:
        p: the parameters.
        theta: inputs theta_1..theta_3 (rad).
        theta_dot: their rates (rad/s).
        theta_ddot: their accelerations (rad/s^2).

    Returns:
        The state: pose, its rates and accelerations, all four limb angles and theirs.

    Raises:
        SingularConfiguration: J_p singular (e.g. the motion law's start, t = 0).
    """
    pose, theta4, _ = assembled_pose(p.dims, theta)
    return motion_state(p.dims, theta, theta_dot, theta_ddot, pose, theta4)


def motion_law_states(p: Parallel2T1RParams, times: np.ndarray) -> list[State]:
    """States along the motion law at ``times`` (s).

    Args:
        p: the parameters.
        times: times, s.

    Returns:
        One state per time.
    """
    return [state_at(p, *motion_law(float(t))) for t in times]
