"""Constrained dynamics of closed-loop mechanisms: forward (constrained ABA) and inverse (constrained RNEA).

Equation of motion: M a + nle = tau + J^T lambda, J the closure Jacobian (rows of `ClosureRows`),
J a + gamma = 0. Forward dynamics two ways: Pinocchio's proximal `constraintDynamics` on the
equivalent `RigidConstraintModel`s, and a dense KKT solve on the independent rows. Inverse
dynamics: `[S, J^T] [u; lambda] = rnea(q, v, a) - J_ext^T f_ext`; every tree joint's transmitted
wrench is then the RNEA's minus the cut wrenches that act on its subtree.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import scipy.linalg

from mechkit.closures import ClosureRows
from mechkit.exceptions import SingularConfiguration
from mechkit.kinematics import numerical_rank
from mechkit.spatial import cross_rows

#: Relative threshold under which a reaction component's null-space variation counts as zero.
DETERMINACY_TOL = 1e-8


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


def kkt_forward(model: pin.Model, data: pin.Data, q: np.ndarray, v: np.ndarray, tau: np.ndarray, J: np.ndarray, gamma: np.ndarray,
                rows: np.ndarray | None = None) -> ForwardDynamicsResult:
    """Dense KKT solve on independent rows of J (needs J, gamma at (q, v)).

    Args:
        model: the tree's Pinocchio model.
        data: a data of it.
        q: configuration (nq,).
        v: velocity (nv,).
        tau: joint efforts (nv,), N m or N.
        J: closure Jacobian (rows, nv) at q.
        gamma: closure acceleration drift (rows,) at (q, v): J a + gamma = 0.
        rows: a set of independent rows to use (e.g. cached from a regular configuration); chosen
            by pivoted QR when None.
    """
    rows = independent_rows(J) if rows is None else rows
    Ji, gi = J[rows], gamma[rows]
    M = pin.crba(model, data, q)
    M = np.triu(M) + np.triu(M, 1).T
    nle = pin.nonLinearEffects(model, data, q, v)
    n, m = model.nv, len(rows)
    K = np.zeros((n + m, n + m))
    K[:n, :n], K[:n, n:], K[n:, :n] = M, -Ji.T, Ji
    rhs = np.concatenate([tau - nle, -gi])
    try:
        lu = scipy.linalg.lu_factor(K, check_finite=True)
    except (ValueError, np.linalg.LinAlgError) as err:
        raise SingularConfiguration(float("inf"), f"KKT matrix: {err}") from None
    if np.min(np.abs(np.diag(lu[0]))) < 1e-14 * np.max(np.abs(np.diag(lu[0]))):
        raise SingularConfiguration(float(np.linalg.cond(K)), "KKT matrix (singular mass matrix or constraint rows)")
    x = scipy.linalg.lu_solve(lu, rhs)
    a, lam = x[:n], x[n:]
    return ForwardDynamicsResult(a, Ji.T @ lam)


def joint_wrenches_world(model: pin.Model, data: pin.Data) -> np.ndarray:
    """(njoints, 6): data.f rotated to world axes, moment about each joint origin (row 0 unused)."""
    f = np.array([w.vector for w in data.f]).reshape(-1, 2, 3)
    R = np.array([M.rotation for M in data.oMi])
    return np.einsum("jab,jkb->jka", R, f).reshape(-1, 6)


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


@dataclass
class InverseDynamicsProblem:
    """What constrained RNEA needs besides (q, v, a): built once per mechanism.

    Attributes:
        model, data: the Pinocchio model and a scratch data.
        rows: the closure rows the scene solves with.
        full_rows: the closures' full spatial rows (the physical joints), for the determinacy test.
        actuated_v: velocity indices of the actuated joints, in effort order.
        actuated_names: their joint names.
        cut_names: names of the cut joints, in `rows.cuts` order.
    """

    model: pin.Model
    data: pin.Data
    rows: ClosureRows
    full_rows: ClosureRows
    actuated_v: np.ndarray
    actuated_names: tuple[str, ...]

    def __post_init__(self) -> None:
        self.incidence = subtree_incidence(self.model, self.rows)
        self.affected = np.flatnonzero(np.any(self.incidence != 0, axis=1))
        self.cut_names = tuple(c.closure.name for c in self.rows.cuts)
        self.tree_names = tuple(self.model.names[1:])
        self.joint_names = self.tree_names + self.cut_names
        parents = self.model.parents
        self.supports = tuple(parents[i] == 0 for i in range(1, self.model.njoints)) + tuple(
            self.model.frames[c.frame_a].parentJoint == 0 or self.model.frames[c.frame_b].parentJoint == 0
            for c in self.rows.cuts)
        self.untested = (None,) * len(self.joint_names)


def inverse_dynamics(p: InverseDynamicsProblem, q: np.ndarray, v: np.ndarray, a: np.ndarray,
                     fext: pin.StdVec_Force | list[pin.Force] | None = None, determinacy: bool = True,
                     distribution: str = "min_norm") -> InverseDynamicsResult:
    """Actuator efforts and every joint's reaction for a motion (q, v, a) that satisfies the closures.

    Args:
        p: the problem (model, rows, actuators).
        q: configuration (nq,).
        v: velocity (nv,).
        a: acceleration (nv,); it must satisfy J a + gamma = 0.
        fext: optional external forces per joint (Pinocchio local frames), e.g. thrust.
        determinacy: run the rank test that flags indeterminate components (one SVD of the full
            spatial rows); without it `JointReaction.determinate` is None (not tested).
        distribution: where [S, J^T] has a null space (redundant actuation or rows), which solution:
            "min_norm" (smallest `|[u; lambda]|`) or "min_effort" (smallest `|u|`, then smallest `|lambda|`).

    Raises:
        SingularConfiguration: [S, J^T] has lost rank where it must not (efforts undetermined).
    """
    model, data, rows = p.model, p.data, p.rows
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    J = rows.jacobian(data)
    b = pin.rnea(model, data, q, v, a) if fext is None else pin.rnea(model, data, q, v, a, fext)
    na, nv = len(p.actuated_v), model.nv
    A = np.zeros((nv, na + rows.size))
    A[p.actuated_v, np.arange(na)] = 1.0
    A[:, na:] = J.T
    cond = np.nan
    square = A.shape[0] == A.shape[1]
    if square and not determinacy:
        try:
            x = np.linalg.solve(A, b)
        except np.linalg.LinAlgError:
            raise SingularConfiguration(float("inf"), "[S, J^T]: efforts and multipliers undetermined") from None
        if not np.all(np.isfinite(x)):
            raise SingularConfiguration(float("inf"), "[S, J^T]: efforts and multipliers undetermined")
    else:
        U, s, Vt = np.linalg.svd(A, full_matrices=True)
        r = numerical_rank(s)
        if r < nv and np.linalg.norm(U[:, r:].T @ b) > 1e-9 * max(np.linalg.norm(b), 1.0):
            raise SingularConfiguration(float(s[0] / s[-1]) if s[-1] > 0 else float("inf"),
                                        "[S, J^T] does not span the required generalised force: the actuators cannot hold this motion")
        x = Vt[:r].T @ ((U[:, :r].T @ b) / s[:r])
        cond = float(s[0] / s[r - 1])
        if distribution == "min_effort" and r < A.shape[1]:
            x = _least_effort(x, Vt[r:].T, na)
        elif distribution not in ("min_norm", "min_effort"):
            raise ValueError(f"distribution {distribution!r}: expected 'min_norm' or 'min_effort'")
    u, lam = x[:na], x[na:]
    W, P = cut_wrench_arrays(data, rows, lam)
    tree = subtract_cut_wrenches(joint_wrenches_world(model, data), data, p.affected, p.incidence, W, P)
    wrenches = np.vstack([tree[1:], W])
    flags, effort_flags = _determinate_flags(p, q) if determinacy else (p.untested, None)
    reactions = {name: JointReaction(w, f, s) for name, w, f, s in zip(p.joint_names, wrenches, flags, p.supports)}
    efforts = dict(zip(p.actuated_names, u.tolist()))
    return InverseDynamicsResult(efforts, reactions, lam, cond, effort_flags)


def _least_effort(x: np.ndarray, N: np.ndarray, na: int) -> np.ndarray:
    """Move x along the null space N to the smallest efforts |u|, then the smallest multipliers."""
    z = -np.linalg.lstsq(N[:na], x[:na], rcond=None)[0]
    x = x + N @ z
    keep = N @ scipy.linalg.null_space(N[:na]) if na else N
    if keep.size:
        x = x - keep @ np.linalg.lstsq(keep[na:], x[na:], rcond=None)[0]
    return x


def _determinate_flags(p: InverseDynamicsProblem, q) -> tuple[np.ndarray, dict[str, bool]]:
    """Which reaction components static equilibrium fixes, tested on the full spatial rows.

    A component is determinate when it does not change along the null space of [S, J_full^T]
    (Wojtyra and Fraczek 2013): such a null vector is a self-stress (cut forces, and actuator
    efforts, in equilibrium with no load). Frames must be current at q. Returns the (joints, 6)
    reaction flags and the effort flags by actuated joint.
    """
    model, data = p.model, p.data
    Jf = p.full_rows.jacobian(data)
    na = len(p.actuated_v)
    A = np.zeros((model.nv, na + p.full_rows.size))
    A[p.actuated_v, np.arange(na)] = 1.0
    A[:, na:] = Jf.T
    _, s, Vt = np.linalg.svd(A, full_matrices=True)
    r = numerical_rank(s)
    null = Vt[r:]
    variation = np.zeros((len(p.joint_names), 6))
    effort_variation = np.abs(null[:, :na]).max(axis=0, initial=0.0) if na else np.zeros(0)
    zero_tree = np.zeros((model.njoints, 6))
    for x in null:
        # a self-stress: cut wrenches with no load; the tree joints carry what the cuts push in
        W, P = cut_wrench_arrays(data, p.full_rows, x[na:])
        tree = subtract_cut_wrenches(zero_tree, data, p.affected, p.incidence, W, P)
        variation = np.maximum(variation, np.abs(np.vstack([tree[1:], W])))
    scale = max(variation.max(initial=0.0), effort_variation.max(initial=0.0), 1e-300)
    effort_flags = {name: bool(d <= DETERMINACY_TOL * scale) for name, d in zip(p.actuated_names, effort_variation)}
    return variation <= DETERMINACY_TOL * scale, effort_flags
