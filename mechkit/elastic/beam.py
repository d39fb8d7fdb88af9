"""A straight uniform beam (axial, Euler-Bernoulli bending, St Venant torsion; no shear deformation):
its 12x12 stiffness and its 6x6 compliance as a cantilever.

Coordinates are those the end points are given in (a link's frame); each end's displacement is the
twist [translation of the end, rotation] and its load the wrench [force, moment about the end].
"""

from __future__ import annotations

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.elastic.sections import Section


def local_axes(start: np.ndarray, end: np.ndarray, axis1: np.ndarray) -> tuple[float, np.ndarray]:
    """The beam's length and axes.

    Args:
        start: (3,) the beam's start (m).
        end: (3,) its end (m).
        axis1: (3,) the direction I1 is about (its part along the beam is dropped).

    Returns:
        The length (m) and the axes (3, 3): rows x (start to end), y (axis1 made normal to x), z = x cross y.

    Raises:
        InvalidParameters: axis1 along the beam (no bending axis can be read from it).
    """
    x = np.asarray(end, dtype=float) - np.asarray(start, dtype=float)
    length = float(np.linalg.norm(x))
    x = x / length
    y = axis1 - np.dot(axis1, x) * x
    if np.linalg.norm(y) < 1e-6:
        raise InvalidParameters(
            "axis1", axis1, "lies along the beam: give the direction I1 is about, normal to the beam"
        )
    y = y / np.linalg.norm(y)
    return length, np.array([x, y, np.cross(x, y)])


def local_stiffness(length: float, s: Section) -> np.ndarray:
    """The beam's stiffness in its own axes (I1 about y, I2 about z).

    Args:
        length: the beam's length (m).
        s: its section.

    Returns:
        (12, 12) stiffness, degrees of freedom [u1, theta1, u2, theta2] (m, rad; N, N m).
    """
    L = length
    k = np.zeros((12, 12))
    axial, torsion = s.E * s.A / L, s.G * s.J / L
    for a, b, value in ((0, 6, axial), (3, 9, torsion)):
        k[np.ix_([a, b], [a, b])] = value * np.array([[1.0, -1.0], [-1.0, 1.0]])
    # bending in x-y (uy, theta_z; E I2) and in x-z (uz, theta_y; E I1): Hermite cubic, signs of theta_y flipped
    for dofs, EI, sign in (([1, 5, 7, 11], s.E * s.I2, 1.0), ([2, 4, 8, 10], s.E * s.I1, -1.0)):
        c = EI / L**3
        m = c * np.array(
            [
                [12.0, 6 * L, -12.0, 6 * L],
                [6 * L, 4 * L**2, -6 * L, 2 * L**2],
                [-12.0, -6 * L, 12.0, -6 * L],
                [6 * L, 2 * L**2, -6 * L, 4 * L**2],
            ]
        )
        flip = np.array([1.0, sign, 1.0, sign])
        k[np.ix_(dofs, dofs)] = m * flip[:, None] * flip[None, :]
    return k


def stiffness(start: np.ndarray, end: np.ndarray, s: Section) -> np.ndarray:
    """The stiffness of a beam in the coordinates its end points are given in.

    Args:
        start: (3,) the beam's start (m).
        end: (3,) its end (m).
        s: its section (`s.axis1` in the same coordinates).

    Returns:
        (12, 12) stiffness, degrees of freedom [u_start, theta_start, u_end, theta_end].

    Raises:
        InvalidParameters: `s.axis1` along the beam.
    """
    length, axes = local_axes(start, end, s.axis1)
    T = np.kron(np.eye(4), axes)
    return T.T @ local_stiffness(length, s) @ T


def cantilever_compliance(free: np.ndarray, clamp: np.ndarray, s: Section) -> np.ndarray:
    """The compliance of a cantilever beam at its free end.

    Args:
        free: (3,) the loaded end (m).
        clamp: (3,) the clamped end (m).
        s: the section (`s.axis1` in the same coordinates).

    Returns:
        (6, 6) the free end's twist [m, rad] per wrench [N, N m about the free end], in the given coordinates.

    Raises:
        InvalidParameters: `s.axis1` along the beam.
    """
    return np.linalg.inv(stiffness(clamp, free, s)[6:, 6:])
