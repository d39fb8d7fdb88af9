"""The Pinocchio tree of the 2-DOF spherical platform, filled from the paper's kinematics (no closure solve).

Tree joints, as in the xacro: the strut's Hooke joint (hooke_roll, hooke_pitch) and per limb i the motor
r{i}1 and the middle joint r{i}2; the platform joints r{i}3 are the loop cuts. Angles in rad.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mechkit.mechanisms.spherical_2dof import kinematics as kin

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = ["guess", "home", "state", "tree_configuration", "tree_q"]


def tree_configuration(p: kin.Geometry, phi: np.ndarray, theta: np.ndarray) -> dict[str, float]:
    """Every tree joint (rad) at attitude ``phi`` and motor angles ``theta`` (closed with eq. 7).

    Args:
        p: the structural parameters.
        phi: attitude (roll, pitch), rad.
        theta: motor angles (theta_11, theta_21), rad.

    Returns:
        Joint -> angle (rad).
    """
    joints = {"hooke_roll": float(phi[0]), "hooke_pitch": float(phi[1])}
    for k, i in enumerate((1, 2)):
        joints[f"r{i}1"] = float(theta[k])
        joints[f"r{i}2"] = kin.limb_angles(p, i, theta[k], phi)[0]
    return joints


def tree_q(mech: Mechanism, phi: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """Pinocchio configuration q (nq,) of `tree_configuration` (the neutral value elsewhere).

    Args:
        mech: the platform.
        phi: attitude (roll, pitch), rad.
        theta: motor angles (theta_11, theta_21), rad.

    Returns:
        q (nq,).
    """
    q = mech.neutral()
    for joint, value in tree_configuration(mech.params, phi, theta).items():
        q[mech.q_index(joint)] = value
    return q


def home(p: kin.Geometry) -> dict[str, float]:
    """Motor angles (rad) of the home attitude (platform level), branch `kin.BRANCHES`.

    Args:
        p: the structural parameters.

    Returns:
        {"r11", "r21"} -> angle (rad).
    """
    theta = kin.inverse_kinematics(p, (0.0, 0.0), kin.BRANCHES)
    return {"r11": float(theta[0]), "r21": float(theta[1])}


def guess(p: kin.Geometry) -> dict[str, float]:
    """Every tree joint (rad) at the home attitude: the initial guess picking the assembly branch.

    Args:
        p: the structural parameters.

    Returns:
        Joint -> angle (rad).
    """
    return tree_configuration(p, np.zeros(2), kin.inverse_kinematics(p, (0.0, 0.0), kin.BRANCHES))


def state(
    mech: Mechanism,
    phi: np.ndarray,
    phi_d: np.ndarray,
    phi_dd: np.ndarray,
    branches: tuple[int, int] = kin.BRANCHES,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pinocchio (q, v, a) of a platform motion, from the paper's kinematics alone (no closure solve).

    Motor angles by eq. (8); joint rates and accelerations by the limb velocity loops
    (`kin.limb_rates`).

    Args:
        mech: the loaded spherical_2dof mechanism.
        phi: attitude (roll, pitch), rad.
        phi_d: its rates, rad/s.
        phi_dd: its accelerations, rad/s^2.
        branches: the IK branch per limb (+1 / -1).

    Returns:
        (q (nq,), v (nv,), a (nv,)).
    """
    p = mech.params
    theta = kin.inverse_kinematics(p, phi, branches)
    q, v, a = tree_q(mech, phi, theta), np.zeros(mech.model.nv), np.zeros(mech.model.nv)
    omega, alpha = kin.hooke_rates(phi, phi_d, phi_dd)
    for j, joint in enumerate(("hooke_roll", "hooke_pitch")):
        v[mech.v_index(joint)], a[mech.v_index(joint)] = phi_d[j], phi_dd[j]
    for k, i in enumerate((1, 2)):
        rate, acc = kin.limb_rates(p, i, theta[k], phi, omega, alpha)
        for j in range(2):
            v[mech.v_index(f"r{i}{j + 1}")], a[mech.v_index(f"r{i}{j + 1}")] = rate[j], acc[j]
    return q, v, a
