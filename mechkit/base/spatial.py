"""Small 3D helpers shared by the core and the mechanisms' analytic kinematics (numpy only).

Written out by hand: on single 3-vectors `np.cross` costs an order of magnitude more.
"""

from __future__ import annotations

import numpy as np


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b for two 3-vectors.

    Args:
        a: a 3-vector.
        b: a 3-vector.

    Returns:
        a x b, shape (3,).
    """
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def cross_rows(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross products of two (n, 3) arrays.

    Args:
        a: (n, 3) vectors.
        b: (n, 3) vectors.

    Returns:
        The n cross products, shape (n, 3).
    """
    return np.column_stack(
        (
            a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1],
            a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2],
            a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0],
        )
    )


#: Levi-Civita symbol as a (9, 3) matrix: (a outer b).reshape(9) @ LEVI_CIVITA = a x b.
LEVI_CIVITA = np.zeros((9, 3))
for _i, _j, _k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
    LEVI_CIVITA[3 * _i + _j, _k], LEVI_CIVITA[3 * _j + _i, _k] = 1.0, -1.0


def skew(d: np.ndarray) -> np.ndarray:
    """[d]x, so that skew(d) @ b = d x b.

    Args:
        d: a 3-vector.

    Returns:
        The (3, 3) skew-symmetric matrix of d.
    """
    return np.array([[0.0, -d[2], d[1]], [d[2], 0.0, -d[0]], [-d[1], d[0], 0.0]])


def rot_x(t: float) -> np.ndarray:
    """Rotation matrix about x by t (rad).

    Args:
        t: the angle (rad).

    Returns:
        The (3, 3) rotation matrix.
    """
    c, s = np.cos(t), np.sin(t)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(t: float) -> np.ndarray:
    """Rotation matrix about y by t (rad).

    Args:
        t: the angle (rad).

    Returns:
        The (3, 3) rotation matrix.
    """
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(t: float) -> np.ndarray:
    """Rotation matrix about z by t (rad).

    Args:
        t: the angle (rad).

    Returns:
        The (3, 3) rotation matrix.
    """
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
