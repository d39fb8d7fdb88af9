"""Natural frequencies and mode shapes with the actuators locked, about an assembled pose.

The idealisation's masses sit at the bodies' centres of mass (a beam's body carries its link's mass
and inertia; beams are massless), so the massive degrees of freedom are six per massive body. With
the flexibility F between unit wrenches at those centres (the force method, `ElasticModel`) and their
mass matrix M, K phi = w^2 M phi on the constraint manifold is F M phi = mu phi, mu = 1 / w^2: the
symmetric eigenproblem of M^1/2 F M^1/2 (massless freedoms condensed exactly; directions held rigidly,
mu = 0, have no finite frequency). How many modes are finite is judged on the structure's flexibility
(every section of unit moduli: which directions yield does not depend on how much), not relative to the
softest mode: a near-rigid locked mechanism used to report round-off as a mode of 3e16 Hz.

Modes below a gap, a frequency under `NEAR_MECHANISM` of the next one's, are labelled near-mechanism modes
(every mode under the highest such gap among those computed): motions the structure barely resists (a
joint near a singularity, a spring-loaded freedom, a link far softer than the rest), which a designer reads
as a mechanism more than as a vibration.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import scipy.linalg
import scipy.sparse.linalg

#: Relative eigenvalue mu of the structure under which a mode counts as held rigidly (no finite frequency).
RIGID_TOL = 1e-12
#: A mode below this fraction of the next mode's frequency is a near-mechanism mode (ours: a decade apart).
NEAR_MECHANISM = 0.1


@dataclass(frozen=True)
class Modes:
    """The first natural modes at one pose.

    Attributes:
        frequencies: (n,) natural frequencies (Hz), ascending.
        shapes: (n, bodies, 6) each mode's twist [translation (m), rotation (rad)] of every massive
            body at its centre of mass, world axes, mass-normalised (phi^T M phi = 1).
        bodies: (bodies,) the Pinocchio ids of the massive bodies.
        names: their URDF links.
        centres: (bodies, 3) their centres of mass (world, m).
        near_mechanism: (n,) whether each mode lies below a gap: a frequency under `NEAR_MECHANISM` of the
            next one's (see the module docstring).
    """

    frequencies: np.ndarray
    shapes: np.ndarray
    bodies: np.ndarray
    names: tuple[str, ...]
    centres: np.ndarray
    near_mechanism: np.ndarray


def mass_matrix(model: pin.Model, R: np.ndarray, bodies: np.ndarray) -> np.ndarray:
    """The block-diagonal mass matrix of bodies at their centres of mass: [m I, 0; 0, R I_c R^T] per body.

    Args:
        model: the Pinocchio model (the bodies' masses and inertias).
        R: (njoints, 3, 3) body rotations (world).
        bodies: (k,) the bodies' ids.

    Returns:
        (6k, 6k) the mass matrix (kg, kg m^2), world axes.
    """
    M = np.zeros((6 * len(bodies), 6 * len(bodies)))
    for k, b in enumerate(bodies):
        inertia = model.inertias[int(b)]
        M[6 * k : 6 * k + 3, 6 * k : 6 * k + 3] = inertia.mass * np.eye(3)
        M[6 * k + 3 : 6 * k + 6, 6 * k + 3 : 6 * k + 6] = R[int(b)] @ inertia.inertia @ R[int(b)].T
    return M


def modes(
    model: pin.Model,
    R: np.ndarray,
    bodies: np.ndarray,
    centres: np.ndarray,
    F: np.ndarray,
    n: int,
    names: tuple[str, ...],
    structure: np.ndarray,
    unit: float = 0.0,
) -> Modes:
    """The first `n` natural modes from the flexibility F (6k, 6k) between unit wrenches at the massive
    bodies' centres of mass (`ElasticModel` computes it).

    Args:
        model: the Pinocchio model (the bodies' masses and inertias).
        R: (njoints, 3, 3) body rotations (world).
        bodies: (k,) the massive bodies' ids.
        centres: (k, 3) their centres of mass (world, m).
        F: (6k, 6k) the flexibility (m/N, rad/(N m)), world axes.
        n: modes wanted (fewer come back where directions are held rigidly).
        names: (k,) the bodies' names (their URDF links).
        structure: (6k, 6k) the same flexibility with every section of unit moduli (its rank: the finite
            modes).
        unit: the scale of its eigenvalues (a unit-moduli element of the mechanism's size carrying its
            heaviest body), so that a structure rigid everywhere is not judged against its own round-off.

    Returns:
        The `Modes`, ascending in frequency.
    """
    M = mass_matrix(model, R, bodies)
    blocks = M.reshape(len(bodies), 6, len(bodies), 6)[np.arange(len(bodies)), :, np.arange(len(bodies))]
    w, V = np.linalg.eigh(blocks)  # M is block diagonal: its square root block by block
    root = scipy.linalg.block_diag(*((V * np.sqrt(np.clip(w, 0.0, None))[:, None, :]) @ np.swapaxes(V, 1, 2)))
    reference = np.linalg.eigvalsh(root @ ((structure + structure.T) / 2) @ root)
    finite = int(np.sum(reference > RIGID_TOL * max(float(reference.max(initial=0.0)), unit)))
    A = root @ F @ root
    scale = max(float(np.abs(A).max()), 1e-300)
    A = np.where(np.abs(A) > 1e-30 * scale, A / scale, 0.0)  # no subnormal numbers: they slow LAPACK a thousandfold
    A = (A + A.T) / 2
    if 3 * n < len(A):  # the few largest mu by Lanczos, from a fixed start (the spectrum's top is well separated)
        mu, U = scipy.sparse.linalg.eigsh(A, k=n + 1, which="LA", v0=np.ones(len(A)), tol=0.0)
    else:
        mu, U = np.linalg.eigh(A)
    mu = mu * scale
    order = np.argsort(mu)[::-1]
    mu, U = mu[order], U[:, order]
    finite = min(finite, int(np.sum(mu > 0)))
    n = min(n, finite)
    phi = (F @ root @ U[:, :n]) / mu[:n]
    phi /= np.sqrt(np.einsum("in,ij,jn->n", phi, M, phi))
    every = 1.0 / np.sqrt(mu[: min(n + 1, finite)]) / (2 * np.pi)
    gaps = [k for k in range(len(every) - 1) if every[k] < NEAR_MECHANISM * every[k + 1]]
    near = np.arange(n) <= (gaps[-1] if gaps else -1)  # the cluster below the highest gap
    return Modes(every[:n], phi.T.reshape(n, len(bodies), 6), bodies, names, centres, near)
