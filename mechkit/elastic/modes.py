"""Natural frequencies and mode shapes with the actuators locked, about an assembled pose.

The idealisation's masses sit at the bodies' centres of mass (a beam's body carries its link's mass
and inertia; beams are massless), so the massive degrees of freedom are six per massive body. With
the flexibility F between unit wrenches at those centres (the force method, `ElasticModel`) and their
mass matrix M, K phi = w^2 M phi on the constraint manifold is F M phi = mu phi, mu = 1 / w^2: the
symmetric eigenproblem of M^1/2 F M^1/2 (massless freedoms condensed exactly; directions held rigidly,
mu = 0, have no finite frequency).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import scipy.linalg
import scipy.sparse.linalg

#: Relative eigenvalue mu under which a mode counts as held rigidly (no finite frequency).
RIGID_TOL = 1e-12


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
    """

    frequencies: np.ndarray
    shapes: np.ndarray
    bodies: np.ndarray
    names: tuple[str, ...]
    centres: np.ndarray


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

    Returns:
        The `Modes`, ascending in frequency.
    """
    M = mass_matrix(model, R, bodies)
    blocks = M.reshape(len(bodies), 6, len(bodies), 6)[np.arange(len(bodies)), :, np.arange(len(bodies))]
    w, V = np.linalg.eigh(blocks)  # M is block diagonal: its square root block by block
    root = scipy.linalg.block_diag(*((V * np.sqrt(np.clip(w, 0.0, None))[:, None, :]) @ np.swapaxes(V, 1, 2)))
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
    finite = int(np.sum(mu > RIGID_TOL * max(mu[0], 1e-300)))
    n = min(n, finite)
    phi = (F @ root @ U[:, :n]) / mu[:n]
    phi /= np.sqrt(np.einsum("in,ij,jn->n", phi, M, phi))
    frequencies = 1.0 / np.sqrt(mu[:n]) / (2 * np.pi)
    return Modes(frequencies, phi.T.reshape(n, len(bodies), 6), bodies, names, centres)
