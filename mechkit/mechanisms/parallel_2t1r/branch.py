"""The 2T1R's assembled branch: the paper's example inputs and the pose the URDF model is assembled on.

Tables 1-2 of the paper are lost; the branch `ASSEMBLED` carries the whole motion law with limb III
reachable and starts with every limb at theta_d = 0 (so does its mirror, branch (0, 1)).
"""

from __future__ import annotations

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.parallel_2t1r.kinematics import Dims, Pose, follower_angles, forward_kinematics

#: The assembled branch: (C1 root, alpha root) of `forward_kinematics` (C1 below the chord B1B2,
#: first alpha root) and the root of `follower_angles` (theta_4 = 0 at the motion law's start).
ASSEMBLED = ((1, 0), 0)
#: The joints of the paper's three motors, theta_1..theta_3.
INPUTS = ("R11", "R21", "R31")
#: The paper's example inputs theta_1..theta_3 (rad): 10, 20, 30 deg.
EXAMPLE_INPUTS = np.radians([10.0, 20.0, 30.0])


def assembled_pose(d: Dims, theta: np.ndarray) -> tuple[Pose, float, float]:
    """The assembled pose for inputs theta_1..theta_3 (rad): pose, theta_4 (rad), FK discriminant.

    The branch is the `ASSEMBLED` root index; the root labels of `solve_trig` and of the C1 circle
    intersection are continuous away from double roots, so a fixed index follows a continuous
    motion that stays clear of singular poses.

    Args:
        d: the mechanism's dimensions (m).
        theta: (3,) inputs (rad).

    Returns:
        (the pose, theta_4 (rad), the FK discriminant (-)).

    Raises:
        InvalidParameters: the inputs cannot be assembled (a limb out of reach).
    """
    found = [s for s in forward_kinematics(d, theta) if s.branch == ASSEMBLED[0]]
    if not found:
        raise InvalidParameters("theta", theta, f"no pose on the assembled branch {ASSEMBLED[0]}")
    roots, _ = follower_angles(d, found[0].pose)
    return found[0].pose, roots[ASSEMBLED[1]], found[0].discriminant
