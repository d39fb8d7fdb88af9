"""Static equilibrium: the pose where gravity, the springs and the held inputs balance.

At rest (v = 0) the generalised force on the mechanism is Q(q) = tau_elements(q) - g(q) (the force
elements' loads minus the gravity torques, `pin.computeGeneralizedGravity`); the closures and the
held joints take what lies in the range of G^T, G = [J; S_held], so the pose is in equilibrium where
the reduced force N^T Q vanishes, N a basis of the null space of G (the free motions). The solve
moves along the free motions (each step followed by the closure solve, the held joints kept):
Newton steps on N^T Q with its Jacobian K by central differences along N where K is negative
definite (a stable equilibrium: a displacement meets a restoring force), else a step along N^T Q
itself (downhill in the potential), limited to `MAX_STEP`. The answer reports K's eigenvalues, so a
caller sees an unstable equilibrium for what it is.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin
import scipy.linalg

from mechkit import core
from mechkit.base import arguments
from mechkit.base.exceptions import ClosureNotConverged, InvalidArgument
from mechkit.base.joint_arguments import joint_values
from mechkit.forces import ForceElement, ForceState, generalized_of_wrenches
from mechkit.simulation.declared import default_forces
from mechkit.simulation.prescribed import Drives
from mechkit.simulation.projection import Projection

#: Largest step along the free motions (rad or m per coordinate, ours: a tenth of a radian).
MAX_STEP = 0.1
#: Central-difference step of the reduced stiffness (rad or m).
DIFF_STEP = 1e-6


@dataclass(frozen=True)
class Equilibrium:
    """A static equilibrium.

    Attributes:
        q: (nq,) the pose.
        residual: max |N^T Q| (N m or N) there.
        stiffness: (d,) eigenvalues of the reduced stiffness -K (N m/rad or N/m; all > 0: stable).
        iterations: steps taken.
        basis: (nv, d) orthonormal basis N of the free motions there (the null space of the closures'
            and held joints' rows).
        stiffness_matrix: (d, d) the reduced stiffness -K in that basis (symmetric; N m/rad or N/m).
    """

    q: np.ndarray
    residual: float
    stiffness: np.ndarray
    iterations: int
    basis: np.ndarray
    stiffness_matrix: np.ndarray

    @property
    def stable(self) -> bool:
        """Every free motion meets a restoring force."""
        return bool(np.all(self.stiffness > 0))


def equilibrium(
    mech: Any,
    held: Mapping[str, float] | None = None,
    elements: Sequence[ForceElement] | None = None,
    q0: np.ndarray | None = None,
    tol: float = 1e-10,
    max_iter: int = 200,
) -> Equilibrium:
    """The static equilibrium near q0 with the `held` joints at their values.

    Args:
        mech: the mechanism (`mechkit.Mechanism`).
        held: joint -> value (rad or m) of the inputs held still (default: none held).
        elements: the force elements (default: those its description declares, `default_forces`: the
            springs, dampers, friction and point-to-point elements of its URDF; an MJCF file's are given
            here).
        q0: where to start (default: the home assembly).
        tol: the reduced force to reach (N m or N).
        max_iter: steps allowed.

    Returns:
        The `Equilibrium`: the pose, its residual and the reduced stiffness's eigenvalues (a held pose
        without free motion: residual 0 and no eigenvalue).

    Raises:
        InvalidArgument: a held joint unknown, of several freedoms or not a finite number; q0 not (nq,)
            finite numbers; tol not > 0; max_iter not an integer >= 1; an element not a force element.
        ClosureNotConverged: no equilibrium reached within max_iter steps (the residual is reported).
    """
    model = mech.model
    held = _held(held, mech)
    q0 = mech.home_q if q0 is None else arguments.array("q0", q0, model.nq, batch=False)
    tol = arguments.number("tol", tol, positive=True)
    max_iter = arguments.integer("max_iter", max_iter, minimum=1)
    elements = checked_elements(mech, elements)
    drives = Drives(held=held)
    projection = Projection(mech)
    data = model.createData()
    q = projection.positions(q0, drives, 0.0)
    zero = np.zeros(model.nv)
    split = mech.closure_model.split(drives.all)

    def basis(q: np.ndarray) -> np.ndarray:
        G = np.vstack([mech.closure_jacobian(q), np.eye(model.nv)[split.input_v]])
        return scipy.linalg.null_space(G, rcond=core.RANK_TOL)

    def force(q: np.ndarray) -> np.ndarray:
        return generalized_force(model, data, elements, q, zero)

    def move(q: np.ndarray, N: np.ndarray, z: np.ndarray) -> np.ndarray:
        return projection.positions(pin.integrate(model, q, N @ z), drives, 0.0)

    def reduced(q: np.ndarray, N: np.ndarray) -> np.ndarray:  # the force along the motions at q, in N's frame
        here = basis(q)
        return N.T @ here @ (here.T @ force(q))

    def stiffness(q: np.ndarray, N: np.ndarray) -> np.ndarray:
        cols = [
            (reduced(move(q, N, DIFF_STEP * e), N) - reduced(move(q, N, -DIFF_STEP * e), N)) / (2 * DIFF_STEP)
            for e in np.eye(N.shape[1])
        ]
        K = np.array(cols).T
        return 0.5 * (K + K.T)

    for it in range(max_iter):
        N = basis(q)
        if N.shape[1] == 0:  # the held joints fix the pose: nothing to balance
            return Equilibrium(q, 0.0, np.zeros(0), it, N, np.zeros((0, 0)))
        rho = N.T @ force(q)
        K = stiffness(q, N)
        eig = -np.linalg.eigvalsh(K)
        if np.max(np.abs(rho), initial=0.0) <= tol:
            return Equilibrium(q, float(np.max(np.abs(rho), initial=0.0)), eig, it, N, -K)
        step = -np.linalg.solve(K, rho) if np.all(eig > 0) else rho / max(float(np.max(eig)), 1e-12)
        step *= min(1.0, MAX_STEP / max(float(np.max(np.abs(step))), 1e-300))
        q = move(q, N, step)
    raise ClosureNotConverged(
        float(np.max(np.abs(rho))), tol, max_iter, "no static equilibrium found (the reduced force did not vanish)"
    )


def checked_elements(mech: Any, elements: Sequence[ForceElement] | None) -> list[ForceElement]:
    """The force elements acting at rest: those given (checked), or those the description declares.

    Args:
        mech: the mechanism (`mechkit.Mechanism`).
        elements: force elements, or None: `default_forces(mech)`.

    Returns:
        The elements as a list.

    Raises:
        InvalidArgument: an element not a force element.
    """
    if elements is None:
        return default_forces(mech)
    out = list(elements)
    for k, e in enumerate(out):
        if not isinstance(e, ForceElement):
            raise InvalidArgument(f"elements[{k}]", e, "expected a force element (mechkit.forces)")
    return out


def generalized_force(
    model: pin.Model, data: pin.Data, elements: Sequence[ForceElement], q: np.ndarray, v: np.ndarray
) -> np.ndarray:
    """The generalised force of the elements minus the gravity torques, Q = tau_elements(q, v) - g(q).

    Args:
        model: the tree's Pinocchio model.
        data: its scratch data.
        elements: the force elements.
        q: (nq,) the pose.
        v: (nv,) the velocities (rad/s or m/s).

    Returns:
        (nv,) Q (N m or N); no Coriolis terms (they are the dynamics').
    """
    state = ForceState.at(model, data, q, v)
    tau = -pin.computeGeneralizedGravity(model, data, q)
    for e in elements:
        load = e.load(state)
        tau = tau + (load.generalized if load.generalized is not None else 0.0)
        if load.wrenches is not None:
            tau = tau + generalized_of_wrenches(model, state.data, load.wrenches)
    return tau


def _held(held: Any, mech: Any) -> dict[str, float]:
    """`held` checked: joint -> finite value of a joint of one freedom (rad or m)."""
    if held is None:
        return {}
    if not isinstance(held, Mapping):
        raise InvalidArgument("held", held, "expected a mapping joint -> value (rad or m)")
    values = joint_values("held", held, [], list(mech.model.names[1:]))
    for joint, value in values.items():
        if not isinstance(value, float):
            raise InvalidArgument(f"held[{joint!r}]", held[joint], "a held joint takes one value (rad or m)")
    return values
