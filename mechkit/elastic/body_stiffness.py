"""A body's stiffness at a point from its compliance, with the directions held rigidly told apart.

A direction is held rigidly when no elastic element yields along it: structure, not magnitude, decides, so
it is judged on the same idealisation with every section of unit moduli (`ElasticModel`'s structure), whose
compliance has the same null space whatever each element's stiffness. Judging it on the compliance itself,
relative to its largest entry, called a direction rigid (and the stiffness infinite in every direction)
once one link was made a trillion times softer than the rest. Off the rigid directions the stiffness is the
inverse of the compliance, by its eigenvalues; a direction whose compliance is below what the arithmetic
resolves (`RESOLVABLE` of the largest) is reported held rigidly too, never as a number from round-off.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Compliance of the unit-moduli structure, relative to its largest, under which a direction is held rigidly.
RIGID = 1e-12
#: Compliance, relative to the largest, that double precision still resolves in a 6 x 6 eigenproblem (ours:
#: 64 machine epsilons).
RESOLVABLE = 64 * np.finfo(float).eps
#: Length under which an axis's component along the rigid directions counts as none (of a unit axis).
ALONG = 1e-9


@dataclass(frozen=True)
class BodyStiffness:
    """The stiffness of one body at one point and pose (world axes at the point; [translation, rotation]).

    Attributes:
        body: the body's link.
        point: (3,) the point (world, m).
        compliance: (6, 6) C, positive semi-definite: twist (m, rad) per wrench (N, N m); zero along `rigid`.
        stiffness: (6, 6) K, the inverse of C off the rigid directions (infinite along them: not in K).
        rigid: (6, k) orthonormal directions held rigidly (no elastic element yields along them).
        held: (6,) K_ii (N/m, N m/rad) with every other direction held; inf for an axis with a rigid component.
        free: (6,) 1 / C_ii with every other direction free; inf for an axis within the rigid directions.
    """

    body: str
    point: np.ndarray
    compliance: np.ndarray
    stiffness: np.ndarray
    rigid: np.ndarray
    held: np.ndarray
    free: np.ndarray


def body_stiffness(
    body: str, point: np.ndarray, C: np.ndarray, structure: np.ndarray, unit: float = 0.0
) -> BodyStiffness:
    """The stiffness of a body from its compliance and its structure's.

    Args:
        body: the body's link.
        point: (3,) the point (world, m).
        C: (6, 6) its compliance (m/N, rad/(N m)), world axes at the point.
        structure: (6, 6) the same compliance with every section of unit moduli (its null space: the
            directions held rigidly).
        unit: the compliance a unit-moduli element of the mechanism's size has (`structure`'s own scale, so
            that a structure rigid in every direction is not judged against its own round-off).

    Returns:
        The `BodyStiffness`.
    """
    s, V = np.linalg.eigh(0.5 * (structure + structure.T))
    yielding = s > RIGID * max(float(s.max()), unit)
    P = V[:, yielding]
    lam, U = np.linalg.eigh(P.T @ (0.5 * (C + C.T)) @ P)
    resolved = lam > RESOLVABLE * max(float(lam.max(initial=0.0)), 0.0)
    soft = P @ U[:, resolved]
    rigid = np.hstack([V[:, ~yielding], P @ U[:, ~resolved]])
    compliance = (soft * lam[resolved]) @ soft.T
    stiffness = (soft / lam[resolved]) @ soft.T
    along_rigid = np.linalg.norm(rigid, axis=1) > ALONG
    held = np.where(along_rigid, np.inf, np.diag(stiffness))
    diagonal = np.diag(compliance)
    within_rigid = np.linalg.norm(soft, axis=1) <= ALONG
    free = np.where(within_rigid, np.inf, 1.0 / np.where(within_rigid, 1.0, diagonal))
    return BodyStiffness(body, point, compliance, stiffness, rigid, held, free)
