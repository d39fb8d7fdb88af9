"""Constrained dynamics of closed-loop mechanisms: forward (constrained ABA) and inverse (constrained RNEA).

Equation of motion: M a + nle = tau + J^T lambda, J the closure Jacobian (rows of `ClosureRows`),
J a + gamma = 0. Forward dynamics two ways: Pinocchio's proximal `constraintDynamics` on the
equivalent `RigidConstraintModel`s, and a dense KKT solve on the independent rows. Inverse
dynamics: [S, J^T] [u; lambda] = rnea(q, v, a) - J_ext^T f_ext; every tree joint's transmitted
wrench is then the RNEA's minus the cut wrenches that act on its subtree.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import scipy.linalg

from mechkit.closures import ClosureRows
from mechkit.exceptions import ClosureNotConverged, InvalidParameters, SingularConfiguration
from mechkit.kinematics import numerical_rank
from mechkit.spatial import cross_rows

#: Relative threshold under which a reaction component's null-space variation counts as zero.
DETERMINACY_TOL = 1e-8
#: Lightest body (kg): Pinocchio's inertia sums are exact above its epsilon (2.2e-16 kg); ours, with a margin.
MIN_BODY_MASS = 1e-14
#: Smallest LU pivot of the equilibrated KKT matrix, relative to the largest, of a regular system.
PIVOT_TOL = 1e-14
#: Allowance, in units of the state's own second-order inconsistency, for a result on such a state (ours).
INCONSISTENT_FACTOR = 20.0
#: Largest |J a + gamma| of a forward-dynamics result, relative to max|J_i| max|a| + max|gamma| (ours).
ACCELERATION_TOL = 1e-8


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


def check_body_masses(model: pin.Model) -> None:
    """Refuse bodies lighter than `MIN_BODY_MASS` (massless bodies, mass 0, are fine).

    Pinocchio merges a link's inertia into its joint's body with lever = sum(m c) / max(sum m, eps),
    eps = 2.2e-16 kg, so a body of 1e-17 kg gets a centre of mass near the joint and wrong dynamics
    (the five-bar at density 1e-12 kg/m^3: accelerations 46 % off); above eps the sum is exact.

    Raises:
        InvalidParameters: the lightest such body, by joint name.
    """
    for j in range(1, model.njoints):
        mass = model.inertias[j].mass
        if 0.0 < mass < MIN_BODY_MASS:
            raise InvalidParameters(f"mass of {model.names[j]}", mass, f"below {MIN_BODY_MASS:g} kg, where Pinocchio's inertia "
                                    "arithmetic (an epsilon of 2.2e-16 kg) misplaces the centre of mass; scale the units")


def mass_scaling(M: np.ndarray) -> np.ndarray:
    """diag(M)^(-1/2): the scaling that gives the mass matrix a unit diagonal (1/sqrt(kg) or 1/sqrt(kg m^2)).

    Raises:
        SingularConfiguration: a coordinate with no inertia (zero or negative diagonal, or not finite).
    """
    d = np.diag(M)
    if not np.all(np.isfinite(M)) or np.any(d <= 0):
        raise SingularConfiguration(float("inf"), "mass matrix: a coordinate carries no inertia (or the inertias are not finite)")
    return 1.0 / np.sqrt(d)


def delassus_scale(M: np.ndarray, J: np.ndarray) -> float:
    """max_i |J_i|^2 / max_j M_jj: the Delassus matrix J M^-1 J^T's scale along the heaviest coordinate
    (1/kg for position rows), the unit the proximal mu is given in. The heaviest coordinate sets the
    smallest scale, so a relative mu stays small against every coordinate (the lightest coordinate's
    scale, on the deployable 3e4 times larger, made Pinocchio's compromise on second-order
    inconsistent states up to 150 times worse: 1114 delta against 7.2 delta)."""
    if J.shape[0] == 0:
        return 1.0
    return float(np.max(np.sum(J ** 2, axis=1)) / np.max(np.diag(M)))


def check_closure_acceleration(J: np.ndarray, a: np.ndarray, gamma: np.ndarray, slack: float = 0.0,
                               what: str = "forward dynamics") -> None:
    """Refuse accelerations that violate J a + gamma = 0 beyond `ACCELERATION_TOL` relative to the terms.

    Where a state's velocity is not a motion of the mechanism at second order (a rank change, as on
    the deployable's infinitesimal fold), no acceleration satisfies every row: gamma has a part no
    J a cancels, of size delta = min over a of max |J a + gamma|. That is the state's inconsistency, not
    the solver's error: a result within `INCONSISTENT_FACTOR` delta is accepted there (a compromise
    between the rows, such as Pinocchio's proximal solve makes: measured up to 7.2 delta on the
    deployable's bench states).

    Args:
        slack: an extra allowance (m/s^2 for position rows), e.g. the size of a stabilisation term the
            method measures its own way.

    Raises:
        ClosureNotConverged: max |J a + gamma| above ACCELERATION_TOL (max |J_i| max |a| + max |gamma|)
            + slack (+ INCONSISTENT_FACTOR delta).
    """
    if J.shape[0] == 0:
        return
    residual = float(np.max(np.abs(J @ a + gamma)))
    scale = float(np.max(np.linalg.norm(J, axis=1)) * np.max(np.abs(a), initial=0.0) + np.max(np.abs(gamma)))
    limit = ACCELERATION_TOL * scale + slack
    if residual <= limit:
        return
    delta = float(np.max(np.abs(J @ np.linalg.lstsq(J, -gamma, rcond=None)[0] + gamma)))
    if not residual <= limit + INCONSISTENT_FACTOR * delta:
        raise ClosureNotConverged(residual, limit + INCONSISTENT_FACTOR * delta, 1,
                                  f"{what}: the accelerations violate J a + gamma = 0")


def on_manifold(J: np.ndarray, residual: np.ndarray, v: np.ndarray) -> bool:
    """True where the closure holds to `ACCELERATION_TOL` relative to the rows (max |e| <= tol max |J_i|,
    max |J v| <= tol max |J_i| max |v|): there every method's rows agree, so ours can judge any method."""
    if J.shape[0] == 0:
        return True
    c = float(np.max(np.linalg.norm(J, axis=1)))
    return bool(np.max(np.abs(residual)) <= ACCELERATION_TOL * c
                and np.max(np.abs(J @ v)) <= ACCELERATION_TOL * c * max(float(np.max(np.abs(v), initial=0.0)), 1e-300))


def kkt_forward(model: pin.Model, data: pin.Data, q, v, tau, J: np.ndarray, gamma: np.ndarray,
                rows: np.ndarray | None = None) -> ForwardDynamicsResult:
    """Dense KKT solve on independent rows of J (needs J, gamma at (q, v)).

    The system is equilibrated before the LU (mass matrix to a unit diagonal, each row of J to unit
    norm), so the pivot test is relative to the model's own scale: a model of 1e-12 kg or of
    millimetre links solves like one of kilograms and metres.

    Args:
        rows: a set of independent rows to use (e.g. cached from a regular configuration); chosen
            by pivoted QR when None.

    Raises:
        SingularConfiguration: a pivot below `PIVOT_TOL` of the largest (rows dependent, or no inertia).
        ClosureNotConverged: the solution violates J a + gamma = 0 (`check_closure_acceleration`).
    """
    rows = independent_rows(J) if rows is None else rows
    Ji, gi = J[rows], gamma[rows]
    M = pin.crba(model, data, q)
    M = np.triu(M) + np.triu(M, 1).T
    nle = pin.nonLinearEffects(model, data, q, v)
    n, m = model.nv, len(rows)
    d = mass_scaling(M)
    JD = Ji * d
    norms = np.linalg.norm(JD, axis=1)
    r = 1.0 / np.where(norms > 0, norms, 1.0)
    K = np.zeros((n + m, n + m))
    K[:n, :n], K[:n, n:], K[n:, :n] = d[:, None] * M * d, -(r[:, None] * JD).T, r[:, None] * JD
    rhs = np.concatenate([d * (tau - nle), -r * gi])
    try:
        lu = scipy.linalg.lu_factor(K, check_finite=True)
    except (ValueError, np.linalg.LinAlgError) as err:
        raise SingularConfiguration(float("inf"), f"KKT matrix: {err}") from None
    pivots = np.abs(np.diag(lu[0]))
    if np.min(pivots) < PIVOT_TOL * np.max(pivots):
        raise SingularConfiguration(float(np.linalg.cond(K)), "KKT matrix (equilibrated): dependent constraint rows "
                                    "or a coordinate without inertia")
    x = scipy.linalg.lu_solve(lu, rhs)
    a, lam = d * x[:n], r * x[n:]
    check_closure_acceleration(Ji, a, gi, what="forward dynamics (KKT)")
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


def inverse_dynamics(p: InverseDynamicsProblem, q, v, a, fext=None, determinacy: bool = True,
                     distribution: str = "min_norm") -> InverseDynamicsResult:
    """Actuator efforts and every joint's reaction for a motion (q, v, a) that satisfies the closures.

    Args:
        p: the problem (model, rows, actuators).
        q, v, a: configuration, velocity, acceleration (a must satisfy J a + gamma = 0).
        fext: optional external forces per joint (Pinocchio local frames), e.g. thrust.
        determinacy: run the rank test that flags indeterminate components (one SVD of the full
            spatial rows); without it `JointReaction.determinate` is None (not tested).
        distribution: where [S, J^T] has a null space (redundant actuation or rows), which solution:
            "min_norm" (smallest |[u; lambda]|) or "min_effort" (smallest |u|, then smallest |lambda|).

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
