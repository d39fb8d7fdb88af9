"""Constrained dynamics of closed-loop mechanisms: forward (constrained ABA) and inverse (constrained RNEA).

Equation of motion: M a + nle = tau + J^T lambda, J the closure Jacobian (rows of `ClosureRows`),
J a + gamma = 0. Forward dynamics (`mechkit.core.forward`) two ways: Pinocchio's proximal
`constraintDynamics` on the equivalent `RigidConstraintModel`s, and a dense KKT solve on the
independent rows. The inverse dynamics is `mechkit.core.inverse`; the result types, the row choice and
the subtree incidence of the cut wrenches are here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import scipy.linalg

from mechkit.base.spatial import cross_rows
from mechkit.core.closures import ClosureRows
from mechkit.core.kinematics import numerical_rank


@dataclass(frozen=True)
class ForwardDynamicsResult:
    """Accelerations (nv,) and generalised constraint force J^T lambda (nv,)."""

    a: np.ndarray
    constraint_force: np.ndarray


@dataclass(frozen=True)
class JointReaction:
    """The wrench [f (N), m (N m)] the parent side exerts on the child side of a joint.

    World frame, moment about the joint origin. `determinate[i]` is False for components that
    static equilibrium does not fix (redundant constraints); their value is the minimum-norm
    convention; `determinate` is None when the test was not run. `support` is True for joints to
    the ground.
    """

    wrench: np.ndarray
    determinate: np.ndarray | None
    support: bool


@dataclass(frozen=True)
class InverseDynamicsResult:
    """Efforts by actuated joint (N m or N) and reactions by joint name (tree and cut joints).

    `efforts_determinate[name]` is False when redundant actuation leaves that effort to the chosen
    distribution (None when the determinacy test was not run); `condition` is that of [S, J^T]
    (nan on the fast square path).
    """

    efforts: dict[str, float]
    reactions: dict[str, JointReaction]
    multipliers: np.ndarray
    condition: float
    efforts_determinate: dict[str, bool] | None = None


def independent_rows(J: np.ndarray) -> np.ndarray:
    """Indices of a maximal set of linearly independent rows (pivoted QR of J^T)."""
    if J.shape[0] == 0:
        return np.zeros(0, dtype=int)
    _, r, piv = scipy.linalg.qr(J.T, mode="economic", pivoting=True)
    d = np.abs(np.diag(r))
    return np.sort(piv[: numerical_rank(d)])




def subtree_incidence(model: pin.Model, rows: ClosureRows) -> np.ndarray:
    """(njoints, cuts): +1 where joint i carries frame_b's body of a cut in its subtree, -1 for frame_a's."""
    G = np.zeros((model.njoints, len(rows.cuts)))
    for c, cut in enumerate(rows.cuts):
        for sign, frame in ((1.0, cut.frame_b), (-1.0, cut.frame_a)):
            j = model.frames[frame].parentJoint
            while j > 0:
                G[j, c] += sign
                j = model.parents[j]
    return G


def cut_wrench_arrays(data: pin.Data, rows: ClosureRows, lam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(cuts, 6) cut wrenches [f, m about p_b] and (cuts, 3) points p_b, world, from the row multipliers."""
    wrenches = rows.wrenches(data, lam)
    W = np.array([np.concatenate([f, m]) for f, m, _ in wrenches]).reshape(-1, 6)
    P = np.array([p for _, _, p in wrenches]).reshape(-1, 3)
    return W, P


def subtract_cut_wrenches(tree: np.ndarray, data: pin.Data, affected: np.ndarray, G: np.ndarray, W: np.ndarray,
                          P: np.ndarray) -> np.ndarray:
    """Tree joint wrenches once the cut wrenches act as external loads on their bodies.

    Each joint transmits what its subtree needs minus what the cut wrenches give it:
    f_i -= sum_c G_ic f_c, m_i -= sum_c G_ic (m_c + (p_c - o_i) x f_c), world axes, about o_i.
    Only the `affected` joints (non-zero rows of G) change; joint origins o_i are read from data.oMi.
    """
    Ga = G[affected]
    F = Ga @ W[:, :3]
    Mo = Ga @ (W[:, 3:] + cross_rows(P, W[:, :3]))
    origins = np.array([data.oMi[int(j)].translation for j in affected]).reshape(-1, 3)
    out = tree.copy()
    out[affected, :3] -= F
    out[affected, 3:] -= Mo - cross_rows(origins, F)
    return out
