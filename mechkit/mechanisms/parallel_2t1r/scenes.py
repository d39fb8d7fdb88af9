"""The 2T1R's scenes: the paper's motion law, and every assembly of the paper's example."""

from __future__ import annotations

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.parallel_2t1r.branch import EXAMPLE_INPUTS, assembled_pose
from mechkit.mechanisms.parallel_2t1r.joint_state import configuration
from mechkit.mechanisms.parallel_2t1r.kinematics import follower_angles, forward_kinematics
from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_DURATION, motion_law
from mechkit.mechanisms.parallel_2t1r.rates import at_rest


def motion_law_scene(mech: Mechanism) -> list[np.ndarray]:
    """Configurations q along the paper's motion law, t = 0..5 s every 0.05 s (analytic positions).

    Args:
        mech: the 2T1R.

    Returns:
        101 configurations (nq,).
    """
    poses = []
    for t in np.linspace(0.0, MOTION_DURATION, 101):
        theta = motion_law(float(t))[0]
        pose, theta4, _ = assembled_pose(mech.params.dims, theta)
        poses.append(configuration(mech, at_rest(pose, theta, theta4)))
    return poses


def motion_law_times(mech: Mechanism, poses: int) -> np.ndarray:
    """Times (s) of the motion-law scene's poses: uniform over the law's 5 s.

    Args:
        mech: the 2T1R.
        poses: the number of poses.

    Returns:
        (poses,) times, s.
    """
    return np.linspace(0.0, MOTION_DURATION, poses)


def example_configurations(mech: Mechanism) -> list[np.ndarray]:
    """Every assembly of the paper's example (theta = 10, 20, 30 deg): each forward pose limb III can
    reach, with each of its theta4 roots, closed by the core's solver from the analytic configuration.

    Args:
        mech: the 2T1R.

    Returns:
        The configurations (nq,), six at the default dimensions.
    """
    out = []
    for sol in forward_kinematics(mech.params.dims, EXAMPLE_INPUTS):
        try:
            roots, _ = follower_angles(mech.params.dims, sol.pose)
        except InvalidParameters:
            continue  # limb III cannot reach this pose
        for theta4 in roots:
            guess = configuration(mech, at_rest(sol.pose, EXAMPLE_INPUTS, theta4))
            out.append(mech.assemble(EXAMPLE_INPUTS, guess=guess))
    return out
