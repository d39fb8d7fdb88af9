"""Small oscillations about a static equilibrium: the eigenvalues of the linearised motion.

On the free motions z of the equilibrium (`Equilibrium.basis` N: the null space of the closures' and the
held joints' rows, v = N z'), the motion linearised about the pose is M z'' + C z' + K z = 0 with
M = N^T M(q) N (Pinocchio's CRBA), K the equilibrium's reduced stiffness (moved along the closed
mechanism, so the constraint forces' geometric stiffness is in it) and C = -N^T dQ/dv N, the force
elements' velocity derivative by central differences along N (exact for linear dampers; the velocity
products of the dynamics cancel in them and vanish at rest). The eigenvalues are those of the first-order
form [[0, I], [-M^-1 K, -M^-1 C]]: s = -zeta w +- i w sqrt(1 - zeta^2) for an underdamped mode.

A constant friction counts here as its regularisation's slope at rest (`mechkit.forces.coulomb`: a
viscous damping of F over the smoothing rate), not as a friction: pass elements without it to see the
motion it lets through.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidArgument
from mechkit.forces import ForceElement
from mechkit.simulation.equilibrium import Equilibrium, checked_elements, generalized_force

#: Velocity step (rad/s or m/s along the unit basis) of the damping's central differences (ours).
VELOCITY_STEP = 1e-6


@dataclass(frozen=True)
class SmallOscillations:
    """The linearised motion about an equilibrium.

    Attributes:
        eigenvalues: (2d,) complex eigenvalues s (1/s), sorted by real part then imaginary part.
        mass: (d, d) reduced mass matrix N^T M N (kg m^2 or kg).
        damping: (d, d) reduced damping C (N m s/rad or N s/m).
        stiffness: (d, d) reduced stiffness K (N m/rad or N/m).
        basis: (nv, d) the free motions N (orthonormal).
    """

    eigenvalues: np.ndarray
    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    basis: np.ndarray

    @property
    def frequencies_hz(self) -> np.ndarray:
        """(k,) undamped natural frequencies |s| / 2 pi (Hz) of the oscillating modes (Im s > 0)."""
        s = self.eigenvalues[self.eigenvalues.imag > 0]
        return np.abs(s) / (2 * np.pi)

    @property
    def damping_ratios(self) -> np.ndarray:
        """(k,) damping ratios -Re s / |s| of the oscillating modes (Im s > 0)."""
        s = self.eigenvalues[self.eigenvalues.imag > 0]
        return -s.real / np.abs(s)


def small_oscillations(mech: Any, eq: Equilibrium, elements: Sequence[ForceElement] | None = None) -> SmallOscillations:
    """The eigenvalues of the motion linearised about a static equilibrium.

    Args:
        mech: the mechanism (`mechkit.Mechanism`).
        eq: its equilibrium (`Mechanism.equilibrium`, with the same elements and held joints).
        elements: the force elements (default: those its description declares, as `equilibrium`'s).

    Returns:
        The `SmallOscillations` (no eigenvalue where the held joints fix the pose).

    Raises:
        InvalidArgument: `eq` not an `Equilibrium` of this mechanism's coordinates; an element not a force
            element.
    """
    model = mech.model
    if not isinstance(eq, Equilibrium) or eq.q.shape != (model.nq,) or eq.basis.shape[0] != model.nv:
        raise InvalidArgument("eq", type(eq).__name__, "expected this mechanism's Equilibrium")
    elements = checked_elements(mech, elements)
    N, K = eq.basis, eq.stiffness_matrix
    d = N.shape[1]
    if d == 0:  # the held joints fix the pose
        return SmallOscillations(np.zeros(0, complex), np.zeros((0, 0)), np.zeros((0, 0)), K, N)
    data = model.createData()
    M = pin.crba(model, data, eq.q)
    Mr = N.T @ (np.triu(M) + np.triu(M, 1).T) @ N
    dQ = [
        generalized_force(model, data, elements, eq.q, VELOCITY_STEP * (N @ e))
        - generalized_force(model, data, elements, eq.q, -VELOCITY_STEP * (N @ e))
        for e in np.eye(d)
    ]
    C = -N.T @ np.array(dQ).T / (2 * VELOCITY_STEP)
    inv = np.linalg.solve(Mr, np.hstack([K, C]))
    A = np.block([[np.zeros((d, d)), np.eye(d)], [-inv[:, :d], -inv[:, d:]]])
    s = np.linalg.eigvals(A).astype(complex)
    order = np.lexsort((s.imag, s.real))
    return SmallOscillations(s[order], Mr, C, K, N)
