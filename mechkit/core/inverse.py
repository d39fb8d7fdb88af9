"""Constrained inverse dynamics (constrained RNEA): actuator efforts and every joint's reaction.

`[S^T, J^T] [u; lambda] = rnea(q, v, a, f_ext) - tau_passive`, S the actuation, J the closure rows.
Every tree joint's transmitted wrench is the RNEA's minus the cut wrenches acting on its subtree
(`ClosureKernel.joint_loads`); a cut joint transmits its cut wrench. Per sample, the work is
Pinocchio's (`computeJointJacobians`, `rnea`, whose placements and joint wrenches are read as views,
`ClosureData.oMi` and `.f`); the rest is the closure kernel, the regularity of the passive block
(certified by a bound where it can be, else judged by singular values: `mechkit.core.rank`), the
solve (`mechkit.core.efforts`), the reactions, and the determinacy test (`mechkit.core.determinacy`).
`inverse_dynamics` is one sample, `inverse_dynamics_batch` N; they give the same numbers.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters
from mechkit.core import efforts, rank
from mechkit.core.determinacy import determinacy, determinacy_one, system
from mechkit.core.inverse_plan import plan, used_placements
from mechkit.core.model import ClosureData, ClosureModel
from mechkit.core.passive_solve import idle_count
from mechkit.core.results import BatchInverseDynamicsResult, InverseDynamicsResult

DISTRIBUTIONS = ("min_norm", "min_effort")


def tree_wrenches(P: np.ndarray, f: np.ndarray) -> np.ndarray:
    """The tree joints' wrenches `data.f` in world axes, about each joint origin.

    Args:
        P: (..., nj, 3, 4) joint placements [R | p] in the world (`data.oMi`).
        f: (..., nj, 6) joint wrenches [f, m] in each joint's LOCAL frame (`data.f`).

    Returns:
        (..., nj - 1, 6) the wrenches of the tree joints (the universe left out), world axes, about
        each joint origin.
    """
    lead, nj = f.shape[:-2], f.shape[-2]
    return (f[..., 1:, :].reshape(*lead, nj - 1, 2, 3) @ P[..., 1:, :, :3].swapaxes(-1, -2)).reshape(*lead, nj - 1, 6)


def inverse_pass(
    cm: ClosureModel, cd: ClosureData, Q: np.ndarray, V: np.ndarray, A: np.ndarray, fexts: Sequence
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Pinocchio's passes (`computeJointJacobians`, `rnea`) of N samples, read.

    Args:
        cm: the closure model.
        cd: its data (workspace).
        Q: (N, nq) configurations.
        V: (N, nv) velocities.
        A: (N, nv) accelerations.
        fexts: N per-sample external forces per joint (`pin.StdVec_Force`, LOCAL frames) or None each.

    Returns:
        Every joint's placement [R | p] (N, nj, 3, 4), `data.J` (N, 6, nv, WORLD), rnea torques
        (N, nv), and the tree joints' wrenches in world axes about each joint origin (N, nj - 1, 6,
        `tree_wrenches`): the reactions before the cut wrenches act.
    """
    model, data = cm.model, cd.pin
    n, nj = len(Q), model.njoints
    T = np.empty((n, nj, 4, 3))  # Pinocchio's placements as they lie (`InversePlan.placements`): one copy each
    Jt = np.empty((n, model.nv, 6))  # data.J transposed: its floats as they lie
    tau = np.empty((n, model.nv))
    f = np.empty((n, nj, 6))
    jacobians, rnea = pin.computeJointJacobians, pin.rnea
    placements, Jw, forces = plan(cm, cd).placements, cd.J.T, cd.f
    for i in range(n):
        q = Q[i]
        jacobians(model, data, q)
        Jt[i] = Jw
        T[i] = placements
        tau[i] = rnea(model, data, q, V[i], A[i]) if fexts[i] is None else rnea(model, data, q, V[i], A[i], fexts[i])
        f[i] = forces
    P = T.transpose(0, 1, 3, 2)
    with np.errstate(under="ignore"):
        return P, Jt.transpose(0, 2, 1), tau, tree_wrenches(P, f)


def _check_regular(
    cm: ClosureModel,
    Jrows: np.ndarray,
    Jw: np.ndarray,
    residuals: np.ndarray,
    generic_rank: int,
    idle: bool,
    certified: np.ndarray | None = None,
) -> dict[int, np.ndarray]:
    """Raise `SingularConfiguration` where a sample's passive block (the closure Jacobian on the
    unactuated motions, `ClosureModel.unactuated`) has lost rank, to what the closure residual resolves
    (`rank.passive_verdict` on its first min(generic rank, columns) singular values: an under-actuated
    mechanism's block has more columns than independent rows), idle freedoms (`passive_solve.idle_count`)
    aside.

    Samples `certified` regular (by `efforts.passive_solve`, else here where the blocks have as many rows as
    columns: `rank.certified_regular` on `rank.regularity_bounds`) pass without singular values. Of
    the others, the resolvable limit grows with s_max and the residual, so their largest of each
    bounds every sample's limit: only samples at or under that bound are judged one by one.

    Returns:
        With `idle` (the mechanism has idle freedoms), sample -> (nv, d) basis of the null space of its
        passive block where that whole space is idle (rods spinning about their own axes); else {}.
    """
    basis = cm.unactuated
    columns = min(basis.shape[1], generic_rank)
    found: dict[int, np.ndarray] = {}
    if min(columns, Jrows.shape[1], len(Jrows)) == 0:
        return found
    blocks = Jrows @ basis
    if certified is None and (Jrows.shape[1] >= basis.shape[1] or (columns == Jrows.shape[1] and not idle)):
        # a wide block's bound is on its smallest singular value, the verdict's; its null space, the idle spins' search
        certified = rank.certified_regular(*rank.regularity_bounds(blocks), residuals)
    if certified is not None and certified.all():
        return found
    judged = np.arange(len(Jrows)) if certified is None else np.flatnonzero(~certified)
    blocks = blocks[judged]
    s = rank.singular_values(blocks)
    if s.shape[1] < columns:
        raise rank.singular_error(s[0], columns, float(residuals[judged[0]]))
    bound = rank.resolvable_singular_value(float(s[:, 0].max()), float(residuals[judged].max()))
    suspects = range(len(s)) if idle else np.flatnonzero(s[:, columns - 1] <= bound)
    for i in suspects:
        sample = int(judged[i])
        _, bad = rank.passive_verdict(s[i][None], columns, residuals[sample][None])
        exact = rank.numerical_rank(s[i])
        if not bad[0] and exact == basis.shape[1]:
            continue
        null = basis @ np.linalg.svd(blocks[i])[2][exact:].T
        count = idle_count(cm, Jw[sample], null)
        if bad[0] and (exact >= columns or count < columns - exact):  # not resolvable, and not idle spins
            raise rank.singular_error(s[i], columns, float(residuals[sample]))
        if idle and count == null.shape[1]:
            found[sample] = null
    return found


def _idle_accelerations(
    cm: ClosureModel, cd: ClosureData, Q: np.ndarray, A: np.ndarray, b: np.ndarray, idle: dict[int, np.ndarray]
) -> np.ndarray:
    """A with each idle freedom's acceleration set by its own dynamics, N^T (M a + nle - tau) = 0.

    No actuator drives an idle freedom and no closure row holds it (J N = 0), so its acceleration is not
    the caller's to choose: a (minimum-norm) kinematic value would ask a ball joint for a torque about the
    rod's axis. The rnea b is affine in a, b(a + N x) = b(a) + M N x.
    """
    A = A.copy()
    for i, N in idle.items():
        M = pin.crba(cm.model, cd.pin, Q[i])
        M = np.triu(M) + np.triu(M, 1).T
        A[i] -= N @ np.linalg.solve(N.T @ M @ N, N.T @ b[i])
    return A


def inverse_dynamics_batch(
    cm: ClosureModel,
    cd: ClosureData,
    Q: np.ndarray,
    V: np.ndarray,
    A: np.ndarray,
    fexts: Sequence | None = None,
    passive: np.ndarray | None = None,
    *,
    determinacy_test: bool = True,
    distribution: str = "min_norm",
    generic_rank: int | None = None,
    idle: bool = False,
) -> BatchInverseDynamicsResult:
    """Actuator efforts and every joint's reaction for N motions (q, v, a) that satisfy the closures.

    Args:
        cm: the closure model.
        cd: its data (workspace; caches row choices).
        Q: (N, nq) configurations.
        V: (N, nv) velocities.
        A: (N, nv) accelerations (J a + gamma = 0).
        fexts: None or N per-sample external forces per joint (`pin.StdVec_Force`, local frames).
        passive: (N, nv) generalised passive forces (springs, dampers; N m or N), or None.
        determinacy_test: flag the components statics leaves undetermined (else the masks are None).
        distribution: where [S^T, J^T] has a null space (redundant actuation or rows), which solution:
            "min_norm" (smallest |[u; lambda]|) or "min_effort" (smallest |u|, then smallest |lambda|).
        generic_rank: the closure's rank at regular configurations (`mobility` at an assembly): refuse
            samples whose passive block has lost rank to what the closure resolves, and give idle freedoms
            the accelerations their own dynamics gives (`_idle_accelerations`); None: neither.
        idle: the mechanism has idle freedoms (`mechkit.core.structure.idle_freedoms` at an assembly).

    Returns:
        Efforts (N, na), reactions (N, n_joints, 6: tree joints, then cut joints; [f, m] world axes,
        about the joint origin), multipliers (N, rows), condition numbers and determinacy masks.

    Raises:
        SingularConfiguration: a passive block not resolvably regular (with `generic_rank`), or
            [S^T, J^T] cannot give the required generalised force (efforts undetermined).
        InvalidParameters: an unknown distribution.
    """
    if distribution not in DISTRIBUTIONS:
        raise InvalidParameters("distribution", distribution, f"expected one of {DISTRIBUTIONS}")
    n, na = len(Q), len(cm.actuated)
    P, J, b, tree = inverse_pass(cm, cd, Q, V, A, [None] * n if fexts is None else fexts)
    if passive is not None:
        b = b - passive
    k = cm.kernel
    with np.errstate(under="ignore"):  # products of tiny lever arms and forces flush to zero harmlessly
        G = used_placements(cm, P)
        world = k.world(G)
        e, Jrows, W = k.rows(world, J, Q)
        residuals = np.linalg.norm(e, axis=-1)
        x, regular, stresses, statics, square = None, None, None, None, False
        if efforts.splits(cm, k.size, distribution):
            x, regular, stresses = efforts.passive_split_batch(cm, cd, Jrows, b, residuals)
        elif determinacy_test and na + k.size == cm.nv and n:  # one inverse bounds A and the passive blocks
            statics = system(cm, Jrows)
            rho, size = efforts.square_bounds(statics), np.square(Jrows).sum(axis=(1, 2))
            regular = None if generic_rank is None else rank.certified_regular(rho, np.sqrt(size), residuals)
            square = bool(np.all(rho * rho > rank.RANK_TOL**2 * (size + np.square(cm.actuation).sum())))
        spins = {} if generic_rank is None else _check_regular(cm, Jrows, J, residuals, generic_rank, idle, regular)
        if spins:
            A = _idle_accelerations(cm, cd, Q, A, b, spins)
            P, J, b, tree = inverse_pass(cm, cd, Q, V, A, [None] * n if fexts is None else fexts)
            if passive is not None:
                b = b - passive
        if statics is None and (x is None or determinacy_test):
            statics = system(cm, Jrows)
        if x is None:  # the condition numbers on first read (`BatchInverseDynamicsResult.condition`)
            x = efforts.solve(cm, statics, b, False, distribution)[0]
        origins, cut_points = P[:, 1:, :, 3], k.points(world)
        reactions = k.joint_loads(W, x[:, na:], origins, cut_points)
        reactions[:, : tree.shape[1]] += tree
        flags = effort_flags = None
        if determinacy_test:
            if square and cm.spatial:  # [S^T, J_full^T] square and certified regular: no self-stress
                stresses = np.zeros((n, na + k.size, 0))
            same = cm.spatial and stresses is not None  # the solve's null spaces are the full rows' ones
            flags, effort_flags = determinacy(
                cm, cd, G, J, Q, origins, cut_points, stresses if same else None, W if cm.spatial else None
            )
    cond, statics = (None, statics) if determinacy_test else (np.full(n, np.nan), None)
    return BatchInverseDynamicsResult(
        cm.joint_names, cm.actuated, x[:, :na], reactions, cm.supports, x[:, na:], cond, flags, effort_flags, statics
    )


def inverse_dynamics(
    cm: ClosureModel,
    cd: ClosureData,
    q: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    fext: pin.StdVec_Force | None = None,
    passive: np.ndarray | None = None,
    *,
    determinacy_test: bool = True,
    distribution: str = "min_norm",
    generic_rank: int | None = None,
    idle: bool = False,
) -> InverseDynamicsResult:
    """One sample of `inverse_dynamics_batch` (the same numbers).

    Args:
        cm: the closure model.
        cd: its data (workspace; caches row choices).
        q: (nq,) configuration.
        v: (nv,) velocity.
        a: (nv,) acceleration (J a + gamma = 0).
        fext: external forces per joint (`pin.StdVec_Force`, LOCAL frames), or None.
        passive: (nv,) generalised passive forces (springs, dampers; N m or N), or None.
        determinacy_test: flag the components statics leaves undetermined (else the masks are None).
        distribution: "min_norm" or "min_effort" (see `inverse_dynamics_batch`).
        generic_rank: the closure's rank at regular configurations, or None (see `inverse_dynamics_batch`).
        idle: the mechanism has idle freedoms (see `inverse_dynamics_batch`).

    Returns:
        Efforts (na,), reactions (n_joints, 6), multipliers (rows,), condition number and determinacy
        masks; the dicts `efforts` and `reactions` are built on first use.

    Raises:
        SingularConfiguration: as `inverse_dynamics_batch`.
        InvalidParameters: an unknown distribution.
    """
    if distribution not in DISTRIBUTIONS:
        raise InvalidParameters("distribution", distribution, f"expected one of {DISTRIBUTIONS}")
    if idle:  # idle spins: their accelerations change the pass (`_idle_accelerations`)
        return inverse_dynamics_batch(
            cm,
            cd,
            q[None],
            v[None],
            a[None],
            [fext],
            None if passive is None else passive[None],
            determinacy_test=determinacy_test,
            distribution=distribution,
            generic_rank=generic_rank,
            idle=idle,
        ).sample(0)
    try:
        return _one_sample(cm, cd, q, v, a, fext, passive, determinacy_test, distribution, generic_rank)
    except FloatingPointError:  # an underflow under the caller's np.errstate(under="raise"): flushed, as the batch does
        with np.errstate(under="ignore"):
            return _one_sample(cm, cd, q, v, a, fext, passive, determinacy_test, distribution, generic_rank)


def _one_sample(
    cm: ClosureModel,
    cd: ClosureData,
    q: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    fext: pin.StdVec_Force | None,
    passive: np.ndarray | None,
    determinacy_test: bool,
    distribution: str,
    generic_rank: int | None,
) -> InverseDynamicsResult:
    """`inverse_dynamics` without idle spins: the batch's steps on one sample, over the data's plan
    (`mechkit.core.inverse_plan`: the world vectors by one product, buffers reused)."""
    model, data, k = cm.model, cd.pin, cm.kernel
    p = cd.inverse
    if p is None or p.cm is not cm:
        p = plan(cm, cd)
    pin.computeJointJacobians(model, data, q)
    b = (
        pin.rnea(model, data, q, v, a) if fext is None else pin.rnea(model, data, q, v, a, fext)
    )  # data.tau: no Pinocchio call below
    if passive is not None:
        b = b - passive
    Jw = cd.J
    p.fill_world()
    world = p.rows_world
    e, Jrows, W = k.rows(world, Jw, q)
    residual = math.sqrt(e.dot(e))
    na, judged = len(cm.actuated), generic_rank is not None
    x, regular, stresses, square, cond = None, None, None, False, math.nan
    square_system = na + k.size == cm.nv  # (not where the split applies: it has more rows)
    if efforts.splits(cm, k.size, distribution):
        x, regular, stresses = efforts.passive_split(cm, cd, Jrows, b, residual)
    elif square_system:  # square: its singular values (cond) are not needed to solve it
        p.statics[:, na:] = Jrows.T
        x, rho = efforts.square_one(p.statics, b, judged or determinacy_test)
        size = rank.squared_norm(Jrows)
        regular = judged and rank.certified_regular(rho, size**0.5, residual)
        square = determinacy_test and rho * rho > rank.RANK_TOL**2 * (size + p.actuation_size)
    if judged and regular is None and cm.unactuated.shape[1]:  # `_check_regular`'s bound, LAPACK directly
        block = Jrows[:, cm.passive_v] if cm.passive_v is not None else Jrows @ cm.unactuated  # the same numbers
        regular = rank.certified_regular(*rank.block_bounds(block), residual)
    if judged and not regular:
        certified = None if regular is None else np.array([regular])
        _check_regular(cm, Jrows[None], Jw[None], np.array([residual]), generic_rank, False, certified)
    A = None  # with the determinacy test, [S^T, J^T]: the condition number on first read (`InverseDynamicsResult`)
    if x is None:
        x, cond = efforts.solve(cm, (statics := system(cm, Jrows[None])), b[None], False, distribution)
        x, cond, A = x[0], float(cond[0]), statics[0] if determinacy_test and math.isnan(cond[0]) else None
    elif determinacy_test:
        A = p.statics.copy() if square_system else np.concatenate((cm.actuation.T, Jrows.T), axis=1)
    origins, cut_points = p.origins, k.points(world)
    reactions = k.joint_loads(W, x[na:], origins, cut_points)
    reactions[: model.njoints - 1] += (p.forces @ p.rotations_t).reshape(-1, 6)  # `tree_wrenches`
    flags = effort_flags = None
    if determinacy_test:
        if square and cm.spatial:  # [S^T, J_full^T] square and certified regular: no self-stress
            stresses = np.zeros((na + k.size, 0))
        same = cm.spatial  # the solve's null space is the full rows' one
        flags, effort_flags = determinacy_one(
            cm,
            cd,
            Jw,
            q,
            origins,
            cut_points,
            stresses if same else None,
            W if same else None,
            p.full_world,
            p.full_statics,
        )
    return InverseDynamicsResult(
        cm.joint_names, cm.actuated, x[:na], reactions, cm.supports, x[na:], cond, flags, effort_flags, A
    )


def multiplier_reactions(cm: ClosureModel, cd: ClosureData, q: np.ndarray, lam: np.ndarray) -> np.ndarray:
    """What closure-row multipliers alone transmit through every joint: the reactions of a self-stress,
    with no load and no motion.

    Args:
        cm: the closure model.
        cd: its data (workspace).
        q: (nq,) configuration.
        lam: (rows,) closure-row multipliers.

    Returns:
        (n_joints, 6) [f, m about the joint's point], world axes, in `ClosureModel.joint_names` order.
    """
    pin.computeJointJacobians(cm.model, cd.pin, q)
    G, k = cd.used_placements(), cm.kernel
    return k.joint_loads(k.row_wrenches(G), lam, cd.oMi[1:, :, 3], k.cut_points(G))
