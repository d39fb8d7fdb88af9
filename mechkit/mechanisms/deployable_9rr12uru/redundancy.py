"""The redundant constraint of the 9RR-12URU composite and what it leaves indeterminate.

60 closure rows of rank 59 along the paper's (three-fold symmetric) motions: one self-stress
(`redundancy`), the one-dimensional indeterminate part of the reactions it causes
(`indeterminate_direction`, `indeterminate_reactions`), the second-order test of the seventh DOF
(`second_order_form`: it holds only along those motions) and the mobility with chains removed
(`mobility_without`: each chain is redundant given the two others, eq. 5).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin
from scipy.linalg import null_space

from mechkit import core
from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanism import Mechanism

#: Names of the world reaction components, in wrench order [f, m].
COMPONENTS = ("fx", "fy", "fz", "mx", "my", "mz")


def indeterminate_reactions(result: core.InverseDynamicsResult) -> dict[str, tuple[str, ...]]:
    """Joint -> world reaction components that statics leaves undetermined (from the determinacy
    flags of `Mechanism.inverse_dynamics`); joints whose reaction is fully determinate are absent.

    Args:
        result: an inverse-dynamics result computed with determinacy=True.

    Returns:
        Joint -> names of its undetermined components ("fx" ... "mz").

    Raises:
        InvalidParameters: the result carries no determinacy flags.
    """
    if any(r.determinate is None for r in result.reactions.values()):
        raise InvalidParameters("result", "determinacy=False", "run Mechanism.inverse_dynamics with determinacy=True")
    return {
        joint: tuple(c for c, ok in zip(COMPONENTS, r.determinate) if not ok)
        for joint, r in result.reactions.items()
        if not r.determinate.all()
    }


@dataclass(frozen=True)
class Redundancy:
    """The redundant constraint of the composite at one configuration.

    Attributes:
        singular_values: of the closure Jacobian (descending).
        self_stress: cut name -> (force (N), moment (N m)) world, at the middle hinge, of the unit
            left null vector y of the closure Jacobian (J^T y = 0): the constraint forces that
            balance among themselves, i.e. the direction in which the reactions are indeterminate.
            Each share is a force along the cut's middle hinge (plus, once folding has started, a
            moment normal to it).
        hinge_axes: cut name -> unit middle-hinge axis (world).
    """

    singular_values: np.ndarray
    self_stress: dict[str, tuple[np.ndarray, np.ndarray]]
    hinge_axes: dict[str, np.ndarray]


def _self_stress(mech: Mechanism, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Singular values of the closure Jacobian at q and its last left singular vector y (J^T y = 0),
    signed so that its largest entry is positive. Leaves mech.data at q."""
    U, s, _ = np.linalg.svd(mech.closure_jacobian(q))
    y = U[:, -1]
    return s, y * np.sign(y[np.argmax(np.abs(y))])


def redundancy(mech: Mechanism, q: np.ndarray) -> Redundancy:
    """Self-stress of the composite at q: the redundant combination of closure rows.

    Args:
        mech: the composite.
        q: an assembled configuration (nq,).

    Returns:
        The closure rows' singular values, the self-stress as each URU's share (force, moment; world, at its
            middle hinge) and the middle hinges' axes.
    """
    s, y = _self_stress(mech, q)
    cuts = core.multiplier_reactions(mech.closure_model, mech.closure_data, q, y)[-len(mech.cuts) :]
    pin.framesForwardKinematics(mech.model, mech.data, q)
    stress = {cut.closure.name: (w[:3], w[3:]) for cut, w in zip(mech.cuts, cuts)}
    axes = {cut.closure.name: mech.data.oMf[cut.frame_a].rotation @ cut.closure.axis for cut in mech.cuts}
    return Redundancy(s, stress, axes)


def indeterminate_direction(mech: Mechanism, q: np.ndarray) -> dict[str, np.ndarray]:
    """The one-dimensional indeterminate part of the reactions at q, made explicit.

    Every reaction is R = R_0 + s P with s undetermined by statics: P (joint -> (6,) world wrench,
    parent on child, at the joint point) is the set of reactions that the self-stress alone
    produces (`core.multiplier_reactions`: its closure forces applied to the tree, no gravity, no
    motion), scaled so that max |P| = 1. Components where P vanishes are the determinate ones.

    Args:
        mech: the composite.
        q: an assembled configuration (nq,).

    Returns:
        Joint -> P (6,), world wrench [f, m], max |P| = 1.
    """
    _, y = _self_stress(mech, q)
    loads = core.multiplier_reactions(mech.closure_model, mech.closure_data, q, y)
    scale = float(np.abs(loads).max())
    return {joint: w / scale for joint, w in zip(mech.closure_model.joint_names, loads)}


def second_order_form(mech: Mechanism, q: np.ndarray, h: float = 1e-3) -> tuple[np.ndarray, np.ndarray]:
    """Second-order test of the redundant configuration q: Q(d) = y^T e''(q)[d, d] on ker J.

    y is the self-stress (J^T y = 0), e the closure residual. A first-order motion d (J d = 0)
    continues to a motion only if Q(d) = 0, so the instantaneous DOF count holds for finite motions
    only along the zero set of Q. Central differences with step h (rad, m) on the residual.

    Args:
        mech: the composite.
        q: an assembled configuration (nq,).
        h: the finite-difference step (rad, m).

    Returns:
        ((k, k) matrix of Q, (nv, k) orthonormal basis of ker J in which it is written).
    """
    _, y = _self_stress(mech, q)
    basis = null_space(mech.closure_jacobian(q), rcond=1e-9)

    def along(d: np.ndarray) -> float:
        return float(y @ mech.closure_residual(pin.integrate(mech.model, q, d)))

    k = basis.shape[1]
    Q = np.zeros((k, k))
    for i in range(k):
        for j in range(i, k):
            a, b = h * basis[:, i], h * basis[:, j]
            Q[i, j] = Q[j, i] = (along(a + b) - along(a - b) - along(b - a) + along(-a - b)) / (4.0 * h * h)
    return Q, basis


def chain_joints(chain: str) -> tuple[str, ...]:
    """Tree joints of a URU rod or chain (e.g. "BG": BG_B1, BG_B2, BG_G1, BG_G2).

    Args:
        chain: the rod's or chain's two node letters.

    Returns:
        Joint names.
    """
    return tuple(f"{chain}_{node}{k}" for node in chain for k in (1, 2))


def mobility_without(mech: Mechanism, q: np.ndarray, chains: tuple[str, ...]) -> tuple[int, int]:
    """(DOF, redundant rows) of the composite at q with the given URU chains removed.

    Args:
        mech: the composite.
        q: an assembled configuration (nq,).
        chains: the URU chains removed (node-letter pairs, e.g. "BG").

    Returns:
        (DOF, redundant rows).
    """
    J = mech.closure_jacobian(q)
    drop_cols = [mech.v_index(j) for c in chains for j in chain_joints(c)]
    keep_rows, i = [], 0
    for cut in mech.cuts:
        if cut.closure.name[:-2] not in chains:
            keep_rows += list(range(i, i + cut.size))
        i += cut.size
    sub = np.delete(J[keep_rows], drop_cols, axis=1)
    rank = core.numerical_rank(np.linalg.svd(sub, compute_uv=False))
    return sub.shape[1] - rank, sub.shape[0] - rank
