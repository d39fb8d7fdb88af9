"""Closed-loop kinematics: closure solve, velocity and acceleration projection, mobility, singularity.

All functions work on a `ClosureRows` set over a Pinocchio model. "Inputs" are the joint
coordinates that are given (actuated joints, or any chosen set); the others are solved for.
Only one-coordinate joints (revolute, prismatic) can be inputs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin
from scipy.linalg import lapack

from mechkit.base.exceptions import ClosureNotConverged, SingularConfiguration
from mechkit.core.closures import ClosureRows

#: Relative singular-value threshold for numerical rank decisions.
RANK_TOL = 1e-9
#: Closure solvers of `solve_closure` (and `Mechanism.assemble`).
ASSEMBLY_METHODS = ("newton", "lm")
#: Closure residual the assembly solves to by default (`Mechanism.assemble`'s tol; m for position rows).
CLOSURE_TOL = 1e-12
#: Machine epsilon of float64 (the rounding floor of a residual).
EPS = float(np.finfo(float).eps)
#: Margin above the resolvable smallest singular value below which a configuration counts as singular.
SINGULAR_MARGIN = 3.0


@dataclass(frozen=True)
class Mobility:
    """Numerical mobility at a configuration.

    Attributes:
        dof: nv - rank(J): degrees of freedom.
        rows: number of closure rows kept.
        rank: rank of the closure Jacobian.
        redundant: rows - rank: redundant constraints.
        singular_values: of the closure Jacobian, descending.
    """

    dof: int
    rows: int
    rank: int
    redundant: int
    singular_values: np.ndarray


def update_kinematics(model: pin.Model, data: pin.Data, q: np.ndarray) -> None:
    """Joint placements, frame placements and joint Jacobians at q."""
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)


def numerical_rank(s: np.ndarray) -> int:
    """Rank from descending singular values, relative to the largest."""
    return int(np.sum(s > RANK_TOL * max(s[0], 1e-300))) if s.size else 0


def mobility(rows: ClosureRows, data: pin.Data, q: np.ndarray) -> Mobility:
    """Degrees of freedom and redundant constraints from the rank of the closure Jacobian at q."""
    update_kinematics(rows.model, data, q)
    J = rows.jacobian(data)
    s = np.linalg.svd(J, compute_uv=False) if J.size else np.zeros(0)
    r = numerical_rank(s)
    return Mobility(rows.model.nv - r, rows.size, r, rows.size - r, s)


@dataclass(frozen=True)
class ClosureSolve:
    """A solved closure: configuration q, Newton steps taken, residuals e (rows,) and Jacobian J (rows, nv)
    at q (None when not asked for)."""

    q: np.ndarray
    iterations: int
    residual: np.ndarray
    jacobian: np.ndarray | None


def _evaluate(rows: ClosureRows, data: pin.Data, q: np.ndarray,
              jacobian: bool = True) -> tuple[np.ndarray, np.ndarray | None, float]:
    if jacobian:
        pin.computeJointJacobians(rows.model, data, q)
        e, J = rows.evaluate(data)
    else:
        pin.forwardKinematics(rows.model, data, q)
        e, J = rows.residual(data), None
    return e, J, float(np.sqrt(e @ e))


def _newton_step(J: np.ndarray, e: np.ndarray) -> np.ndarray:
    """Minimum-norm x with J x = -e: LAPACK gesv when J is square and regular, else lstsq."""
    if J.shape[0] == J.shape[1]:
        _, _, x, info = lapack.dgesv(J, e)
        if info == 0:
            return -x
    return -np.linalg.lstsq(J, e, rcond=None)[0]


def newton_closure(rows: ClosureRows, data: pin.Data, q0: np.ndarray, free_v: np.ndarray, *,
                   tol: float = 1e-12, max_iter: int = 60, method: str = "newton",
                   jacobian_at_solution: bool = True) -> ClosureSolve:
    """`solve_closure`'s solve, returning the residual (and, when `jacobian_at_solution`, the Jacobian) at
    the solution too; data then holds the joint placements (and Jacobians) at q, not the frame
    placements. Without `jacobian_at_solution` a trial point's Jacobian is evaluated only to step from it."""
    model = rows.model
    q = q0.copy()
    e, J, norm = _evaluate(rows, data, q)
    damping = 1e-3
    it = 0
    at_q = True  # data holds q (not a rejected trial)
    for it in range(max_iter):
        if norm <= tol:
            return ClosureSolve(q, it, e, J)
        if J is None:  # data holds q: the accepted trial
            e, J, norm = _evaluate(rows, data, q)
        Jf = J[:, free_v]
        if method == "lm":
            step_free = -np.linalg.solve(Jf.T @ Jf + damping * np.eye(Jf.shape[1]), Jf.T @ e)
        else:
            step_free = _newton_step(Jf, e)
        step = np.zeros(model.nv)
        step[free_v] = step_free
        alpha = 1.0
        while True:
            trial = pin.integrate(model, q, alpha * step)
            e_trial, J_trial, n_trial = _evaluate(rows, data, trial, jacobian_at_solution)
            if n_trial < norm or alpha < 1e-6:
                break
            alpha *= 0.5
        if not np.isfinite(n_trial):
            at_q = False
            break
        if method == "lm":
            damping = damping * 0.3 if n_trial < norm else damping * 10.0
        q, e, J, norm = trial, e_trial, J_trial, n_trial
        if alpha < 1e-6 and norm > tol:
            break
    if norm <= tol:
        return ClosureSolve(q, it + 1, e, J)
    if not at_q or J is None:
        pin.computeJointJacobians(model, data, q)
    raise ClosureNotConverged(float(norm), tol, it + 1, "the loop cannot close from this guess, or at all, for these inputs")


def solve_closure(rows: ClosureRows, data: pin.Data, q0: np.ndarray, free_v: np.ndarray, *,
                  tol: float = 1e-12, max_iter: int = 60, method: str = "newton") -> tuple[np.ndarray, int]:
    """Solve the closure for the velocity directions `free_v`, keeping the others fixed.

    Gauss-Newton with a minimum-norm step (LAPACK gesv on a square regular block, else lstsq:
    redundant rows allowed) or Levenberg-Marquardt, both with a backtracking line search on |e|.
    Leaves `data` current at q (joint and frame placements, joint Jacobians).

    Args:
        rows: the closure rows.
        data: Pinocchio data (scratch).
        q0: starting configuration; its fixed coordinates are the inputs.
        free_v: indices (into v) of the coordinates to solve for.
        tol: residual norm to reach.
        max_iter: iteration cap.
        method: "newton" or "lm".

    Returns:
        (q, iterations).

    Raises:
        ClosureNotConverged: the residual did not reach tol (the linkage may not assemble there).
    """
    try:
        out = newton_closure(rows, data, q0, free_v, tol=tol, max_iter=max_iter, method=method)
    finally:
        pin.updateFramePlacements(rows.model, data)
    return out.q, out.iterations


def passive_condition(J: np.ndarray, free_v: np.ndarray, independent_rows: int) -> float:
    """Condition number of the passive block restricted to the generic rank (inf when singular)."""
    s = np.linalg.svd(J[:, free_v], compute_uv=False)
    return float(_verdict(s[None], independent_rows, np.array([CLOSURE_TOL]), True)[0][0])


def resolvable_singular_value(s_max: float | np.ndarray, residual: float | np.ndarray) -> float | np.ndarray:
    """The smallest singular value of the passive block that a closure solved to `residual` can resolve.

    Near a singularity the closure residual grows quadratically in the passive coordinates, e ~ s_max
    dx^2, while a regular pose has e ~ s_min dx. A solve that stopped at |e| = r therefore leaves the
    passive coordinates uncertain by sqrt(r / s_max) and cannot tell s_min from zero once s_min is
    below sqrt(r s_max) (same units as the rows: m for position rows). Newton converges only linearly
    at a singular point, so there it stops near its tolerance (`CLOSURE_TOL`), while at a regular pose
    it overshoots to rounding; r is floored at rounding, eps s_max. Measured on the five-bar with its
    distal links collinear (tests/test_bad_inputs_singular.py): at the singular input s_min is 0.6 to
    0.9 sqrt(r s_max); 1e-8 rad away it is over 30 times that. `SINGULAR_MARGIN` (3, ours) sits above
    the singular floor. Element-wise on arrays.

    Args:
        s_max: largest singular value of the passive block (the rows' scale).
        residual: closure residual norm reached at the configuration.
    """
    out = SINGULAR_MARGIN * np.sqrt(np.maximum(residual, EPS * s_max) * s_max)
    return float(out) if np.ndim(out) == 0 else out


def _verdict(s: np.ndarray, independent_rows: int, residual: np.ndarray,
             allow_singular: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per sample of s (N, m): condition number, not-resolvable flag and resolvable limit."""
    k = min(independent_rows, s.shape[1])
    if k == 0:
        ones = np.ones(len(s))
        return ones, np.zeros(len(s), dtype=bool), ones * 0.0
    s_max, s_min = s[:, 0], s[:, k - 1]
    positive = s_min > 0
    cond = np.divide(s_max, s_min, out=np.full(len(s), np.inf), where=positive)
    limit = resolvable_singular_value(s_max, residual)
    bad = ~positive | ((s_min < limit) & (not allow_singular))
    return cond, bad, limit


def rejected(s: np.ndarray, independent_rows: int, residual: np.ndarray | float,
             allow_singular: bool = False) -> np.ndarray:
    """(N,) True at the samples of singular values s (N, m) that `judge_batch` rejects."""
    return _verdict(s, independent_rows, np.broadcast_to(np.asarray(residual, dtype=float), (len(s),)), allow_singular)[1]


def judge_batch(s: np.ndarray, independent_rows: int, residual: np.ndarray | float,
                allow_singular: bool = False) -> np.ndarray:
    """`judge_passive` for N samples: condition numbers (N,) from singular values (N, m) and residuals (N,).

    Raises:
        SingularConfiguration: at the first sample that `judge_passive` rejects.
    """
    residual = np.broadcast_to(np.asarray(residual, dtype=float), (len(s),))
    cond, bad, _ = _verdict(s, independent_rows, residual, allow_singular)
    if bad.any():
        i = int(np.argmax(bad))
        raise singular_error(s[i], independent_rows, float(residual[i]))
    return cond


def singular_error(s: np.ndarray, independent_rows: int, residual: float) -> SingularConfiguration:
    """The error for a passive block with singular values s (m,) that `judge_passive` rejects."""
    cond, _, limit = _verdict(s[None], independent_rows, np.array([residual]), False)
    k = min(independent_rows, s.size)
    return SingularConfiguration(float(cond[0]), f"passive block of the closure Jacobian: smallest singular value "
                                 f"{s[k - 1]:.2e} below the {limit[0]:.2e} a closure residual of {residual:.1e} "
                                 "resolves (inputs do not determine the motion)")


def judge_passive(s: np.ndarray, independent_rows: int, residual: float = CLOSURE_TOL,
                  allow_singular: bool = False) -> float:
    """Condition number of the passive block from its singular values; raises where it is not resolvable.

    Args:
        s: singular values of the passive block, descending.
        independent_rows: the closure's generic rank.
        residual: closure residual norm at the configuration.
        allow_singular: only an exactly rank-deficient block raises.

    Raises:
        SingularConfiguration: smallest singular value (on the generic rank) zero, or below
            `resolvable_singular_value` unless `allow_singular`.
    """
    return float(judge_batch(np.asarray(s)[None], independent_rows, np.array([residual]), allow_singular)[0])


def check_regular(rows: ClosureRows, data: pin.Data, q: np.ndarray, free_v: np.ndarray, independent_rows: int) -> None:
    """Raise `SingularConfiguration` where the inputs (all but `free_v`) do not determine the motion at q
    (or at any sample of a (N, nq) q), to what the closure resolves (`judge_passive`)."""
    G, J, _ = rows.gather(data, np.atleast_2d(q))
    e, Jc = rows.evaluator.evaluate(G, J)
    judge_batch(np.linalg.svd(Jc[..., free_v], compute_uv=False), independent_rows, np.linalg.norm(e, axis=-1))


class Conditioned(np.ndarray):
    """A kinematic result (velocities or accelerations) with the condition number of the passive block
    it was solved with (`condition`, s_max / s_min on the generic rank, the largest over the samples of
    a batch; nan on derived arrays)."""

    condition: float = float("nan")


def passive_solve(J: np.ndarray, inputs: np.ndarray, input_v: np.ndarray, free_v: np.ndarray,
                  rhs: np.ndarray | None = None, svd: tuple | None = None) -> np.ndarray:
    """x (N, nv) with x[input_v] = inputs (N, k) and J_free x_free = -(J_in x_in + rhs) for J (N, rows, nv):
    one batched LU solve where the passive block is square, else the least-squares solution from its
    thin SVD (`svd` = (U, s, Vt) when already computed; the block has full column rank where
    `judge_batch` accepted it)."""
    b = (J[..., input_v] @ inputs[..., None])[..., 0]
    if rhs is not None:
        b = b + rhs
    Jf = J[..., free_v]
    x = np.empty(J.shape[:-2] + J.shape[-1:])
    x[..., input_v] = inputs
    if Jf.shape[-1] == 0:
        return x
    if svd is None and Jf.shape[-2] == Jf.shape[-1]:
        try:
            x[..., free_v] = -np.linalg.solve(Jf, b[..., None])[..., 0]
            return x
        except np.linalg.LinAlgError:
            pass
    U, s, Vt = np.linalg.svd(Jf, full_matrices=False) if svd is None else svd
    with np.errstate(divide="ignore", invalid="ignore"):
        x[..., free_v] = -(np.swapaxes(Vt, -1, -2) @ ((np.swapaxes(U, -1, -2) @ b[..., None])[..., 0] / s)[..., None])[..., 0]
    return x


def check_determined(free_v: np.ndarray, independent_rows: int) -> None:
    """Raise `SingularConfiguration` when more coordinates are free than the closure has independent rows."""
    if free_v.size > independent_rows:
        raise SingularConfiguration(float("inf"), f"{free_v.size} free coordinates but only {independent_rows} independent "
                                    "closure rows: the inputs do not determine the motion (give more inputs)")


def project_batch(J: np.ndarray, inputs: np.ndarray, input_v: np.ndarray, free_v: np.ndarray, independent_rows: int,
                  rhs: np.ndarray | None = None, *, residual: np.ndarray | float = CLOSURE_TOL,
                  allow_singular: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """`project_velocity` for N samples: J (N, rows, nv), inputs (N, k), rhs (N, rows), residual (N,).
    One SVD per sample: singular values only for a square passive block (then an LU solve), thin
    factors otherwise (reused for the least-squares solve).

    Returns:
        x (N, nv) and the passive block's condition numbers (N,).

    Raises:
        SingularConfiguration: as `project_velocity`, at the first sample it rejects.
    """
    check_determined(free_v, independent_rows)
    Jf = J[..., free_v]
    factors = None if Jf.shape[-2] == Jf.shape[-1] else np.linalg.svd(Jf, full_matrices=False)
    s = np.linalg.svd(Jf, compute_uv=False) if factors is None else factors[1]
    cond = judge_batch(s, independent_rows, residual, allow_singular)
    return passive_solve(J, inputs, input_v, free_v, rhs, factors), cond


def project_velocity(J: np.ndarray, v_inputs: np.ndarray, input_v: np.ndarray, free_v: np.ndarray,
                     independent_rows: int, rhs: np.ndarray | None = None, *, residual: float = CLOSURE_TOL,
                     allow_singular: bool = False) -> Conditioned:
    """Solve J_free x_free = -(J_in x_in + rhs) for the free coordinates; returns the full vector.

    Used for velocities (rhs = 0) and accelerations (rhs = gamma).

    Args:
        residual: closure residual norm at the configuration (sets what is resolvable).
        allow_singular: return a result below the resolvable singular value instead of raising (its
            `condition` tells how far to trust it); an exactly rank-deficient block still raises.

    Raises:
        SingularConfiguration: the passive block's smallest singular value is below
            `resolvable_singular_value` (the inputs do not determine the motion, to what the closure
            resolves).
    """
    x, cond = project_batch(J[None], np.asarray(v_inputs, dtype=float)[None], input_v, free_v, independent_rows,
                            None if rhs is None else rhs[None], residual=residual, allow_singular=allow_singular)
    return conditioned(x[0], cond)


def conditioned(x: np.ndarray, cond: np.ndarray) -> Conditioned:
    """x as a `Conditioned` carrying the largest of the condition numbers `cond`."""
    out = x.view(Conditioned)
    out.condition = float(np.max(cond))
    return out


def velocities(rows: ClosureRows, data: pin.Data, q: np.ndarray, rates: np.ndarray, input_v: np.ndarray,
               free_v: np.ndarray, independent_rows: int, allow_singular: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Joint velocities (N, nv) and condition numbers (N,) of N samples q (N, nq) from input rates (N, k):
    one Pinocchio pass and one gather per sample, then batched numpy (`project_batch`, judged at each
    sample's closure residual)."""
    G, J, _ = rows.gather(data, q)
    e, Jc = rows.evaluator.evaluate(G, J)
    return project_batch(Jc, rates, input_v, free_v, independent_rows, residual=np.linalg.norm(e, axis=-1),
                         allow_singular=allow_singular)


def accelerations(rows: ClosureRows, data: pin.Data, q: np.ndarray, v: np.ndarray, input_accelerations: np.ndarray,
                  input_v: np.ndarray, free_v: np.ndarray, independent_rows: int,
                  allow_singular: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Joint accelerations (N, nv), J a + gamma = 0, and condition numbers (N,) of N samples (q, v) from
    input accelerations (N, k), as `velocities`; gamma from the joint Jacobians' time derivatives."""
    G, J, dJ = rows.gather(data, q, v)
    ev = rows.evaluator
    e, Jc = ev.evaluate(G, J)
    gamma = ev.drift(G, ev.twists(J, v), ev.twists(dJ, v))
    return project_batch(Jc, input_accelerations, input_v, free_v, independent_rows, gamma,
                         residual=np.linalg.norm(e, axis=-1), allow_singular=allow_singular)
