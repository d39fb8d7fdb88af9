"""The passive solve: the velocity (or acceleration) coordinates the given ones leave free, from the
closure rows J x = -rhs, judged by `mechkit.core.rank`.

x[input_v] is given; J_free x_free = -(J_in x_in + rhs), rhs None for velocities and the drift gamma for
accelerations. One batched LU where every passive block is square and resolvably regular, else the thin
SVD per sample. A block that does not resolvably determine the free coordinates raises
`SingularConfiguration` (unless `allow_singular`); a right-hand side that leaves its range raises
`InconsistentMotion` (unless `least_squares`). Idle freedoms (velocities closing every loop that move
one body on a loop and no other body with mass: `mechkit.core.structure.idle_counts`) are given their
minimum-norm value, not refused.
"""

from __future__ import annotations

import numpy as np

from mechkit.base.exceptions import InconsistentMotion
from mechkit.core import rank
from mechkit.core.model import ClosureModel, InputSplit
from mechkit.core.structure import grouped, idle_counts


def idle_count(cm: ClosureModel, Jw: np.ndarray, N: np.ndarray, tol: float = 1e-9) -> int:
    """How many of the directions N (nv, d) (velocities closing every loop) are idle freedoms: modes
    that move one body on a loop and no other body with mass (`mechkit.core.structure.idle_counts`).

    Args:
        cm: the closure model (its tracked joints, masses, loops and rigid groups).
        Jw: the WORLD joint Jacobians `data.J` (6, nv) at the configuration.
        N: (nv, d) velocity directions closing every loop.
        tol: relative threshold under which a body's motion counts as none.

    Returns:
        The number of idle freedoms among the directions.
    """
    if N.shape[1] == 0:
        return 0
    twists = {int(j): Jw @ (support[:, None] * N) for j, support in zip(cm.tracked, cm.tracked_support)}
    twists, heavy, looped = grouped(twists, set(cm.massive.tolist()), set(cm.on_loops), cm.rigid_groups)
    return sum(idle_counts(twists, heavy, looped, tol).values())


def solve_passive(
    cm: ClosureModel,
    J: np.ndarray,
    Jw: np.ndarray,
    split: InputSplit,
    given: np.ndarray,
    rhs: np.ndarray | None,
    residual: np.ndarray,
    *,
    allow_singular: bool = False,
    least_squares: bool = False,
    judged: bool = False,
) -> tuple[np.ndarray, np.ndarray]:
    """x (N, nv) with x[input_v] = given (N, k) and J_free x_free = -(J_in given + rhs), judged.

    One batched LU where every passive block is square and resolvably regular; else, per sample, the
    thin SVD: its least-squares solution, with idle freedoms at their minimum-norm value.

    Args:
        cm: the closure model.
        J: (N, rows, nv) closure Jacobians.
        Jw: (N, 6, nv) WORLD joint Jacobians (to find idle freedoms).
        split: which velocity coordinates are given (`input_v`) and solved for (`free_v`).
        given: (N, k) the given coordinates' values.
        rhs: (N, rows) or None (velocities); gamma for accelerations.
        residual: (N,) closure residual norms (what the passive block can resolve).
        allow_singular: return a solution where the block is not resolvably regular (still refused
            where it is exactly rank deficient beyond the idle freedoms).
        least_squares: return the least-squares solution where the right-hand side leaves the block's
            range, instead of raising `InconsistentMotion`.
        judged: the blocks were judged regular already (`passive_verdict`): square ones go straight to
            the LU (their condition numbers are then nan).

    Returns:
        x (N, nv) and the passive blocks' condition numbers (N,).

    Raises:
        SingularConfiguration: a block that does not resolvably determine the free coordinates.
        InconsistentMotion: a right-hand side outside the block's range beyond `rank.RANGE_TOL`.
    """
    input_v, free_v = split.input_v, split.free_v
    b = (J[..., input_v] @ given[..., None])[..., 0]
    if rhs is not None:
        b = b + rhs
    Jf = J[..., free_v]
    x = np.empty(J.shape[:-2] + J.shape[-1:])
    x[..., input_v] = given
    columns = free_v.size
    if columns == 0:
        return x, np.ones(len(J))
    square = Jf.shape[-2] == columns
    if square and judged:
        x[..., free_v] = -np.linalg.solve(Jf, b[..., None])[..., 0]
        return x, np.full(len(J), np.nan)
    if square:
        s = rank.singular_values(Jf)
        cond, bad = rank.passive_verdict(s, columns, residual)
        if not bad.any() or allow_singular:
            try:
                x[..., free_v] = -np.linalg.solve(Jf, b[..., None])[..., 0]
                return x, cond
            except np.linalg.LinAlgError:
                pass
    U, s, Vt = np.linalg.svd(Jf, full_matrices=True)
    cond, bad = rank.passive_verdict(s, columns, residual)
    r = np.full(len(J), min(columns, s.shape[1]))
    for i in np.flatnonzero(bad):
        exact = rank.numerical_rank(s[i])
        null = np.zeros((cm.nv, columns - exact))
        null[free_v] = Vt[i, exact:].T
        if exact < columns and idle_count(cm, Jw[i], null) == columns - exact:
            r[i] = exact  # idle freedoms only: their minimum-norm value
        elif not allow_singular or exact < min(columns, s.shape[1]):
            raise rank.singular_error(s[i], columns, float(residual[i]))
    outside = rank.outside_range(U, r, b)
    scale = np.linalg.norm(b, axis=-1) + np.linalg.norm(b if rhs is None else rhs, axis=-1)
    inconsistent = outside > rank.RANGE_TOL * np.maximum(scale, 1e-300)
    if inconsistent.any() and not least_squares:
        i = int(np.argmax(inconsistent))
        raise InconsistentMotion(
            float(outside[i]),
            float(rank.RANGE_TOL * scale[i]),
            "the closure rows' right-hand side "
            "leaves the range of the passive block: the given motion is not a motion of the "
            "mechanism (at second order: the velocity moves along a freedom that exists only "
            "instantaneously)",
        )
    k = np.arange(s.shape[1])
    proj = np.einsum("nij,ni->nj", U[..., : s.shape[1]], b)
    coef = np.where(k[None, :] < r[:, None], proj / np.where(k[None, :] < r[:, None], s, 1.0), 0.0)
    x[..., free_v] = -np.einsum("nij,ni->nj", Vt[:, : s.shape[1]], coef)
    return x, cond
