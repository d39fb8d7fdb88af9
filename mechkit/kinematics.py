"""Closed-loop kinematics: closure solve, velocity and acceleration projection, mobility, singularity.

All functions work on a `ClosureRows` set over a Pinocchio model. "Inputs" are the joint
coordinates that are given (actuated joints, or any chosen set); the others are solved for.
Only one-coordinate joints (revolute, prismatic) can be inputs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit.closures import ClosureRows
from mechkit.exceptions import ClosureNotConverged, SingularConfiguration

#: Relative singular-value threshold for numerical rank decisions.
RANK_TOL = 1e-9
#: Closure solvers of `solve_closure` (and `Mechanism.assemble`).
ASSEMBLY_METHODS = ("newton", "lm")
#: Closure residual the assembly solves to by default (`Mechanism.assemble`'s tol; m for position rows).
CLOSURE_TOL = 1e-12
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


def solve_closure(rows: ClosureRows, data: pin.Data, q0: np.ndarray, free_v: np.ndarray, *,
                  tol: float = 1e-12, max_iter: int = 60, method: str = "newton") -> tuple[np.ndarray, int]:
    """Solve the closure for the velocity directions `free_v`, keeping the others fixed.

    Gauss-Newton with a minimum-norm step (lstsq: redundant rows allowed) or Levenberg-Marquardt,
    both with a backtracking line search on |e|.

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
    model = rows.model
    q = q0.copy()
    update_kinematics(model, data, q)
    e = rows.residual(data)
    norm = np.linalg.norm(e)
    damping = 1e-3
    it = 0
    for it in range(max_iter):
        if norm <= tol:
            return q, it
        J = rows.jacobian(data)[:, free_v]
        if method == "lm":
            step_free = -np.linalg.solve(J.T @ J + damping * np.eye(J.shape[1]), J.T @ e)
        else:
            step_free = -np.linalg.lstsq(J, e, rcond=None)[0]
        step = np.zeros(model.nv)
        step[free_v] = step_free
        alpha = 1.0
        while True:
            trial = pin.integrate(model, q, alpha * step)
            update_kinematics(model, data, trial)
            e_trial = rows.residual(data)
            n_trial = np.linalg.norm(e_trial)
            if n_trial < norm or alpha < 1e-6:
                break
            alpha *= 0.5
        if not np.isfinite(n_trial):
            break
        if method == "lm":
            damping = damping * 0.3 if n_trial < norm else damping * 10.0
        q, e, norm = trial, e_trial, n_trial
        if alpha < 1e-6 and norm > tol:
            break
    update_kinematics(model, data, q)
    if norm <= tol:
        return q, it + 1
    raise ClosureNotConverged(float(norm), tol, it + 1, "the loop cannot close from this guess, or at all, for these inputs")


def passive_condition(J: np.ndarray, free_v: np.ndarray, independent_rows: int) -> float:
    """Condition number of the passive block restricted to the generic rank (inf when singular)."""
    return _condition(np.linalg.svd(J[:, free_v], compute_uv=False), independent_rows)


def resolvable_singular_value(s_max: float, residual: float) -> float:
    """The smallest singular value of the passive block that a closure solved to `residual` can resolve.

    Near a singularity the closure residual grows quadratically in the passive coordinates, e ~ s_max
    dx^2, while a regular pose has e ~ s_min dx. A solve that stopped at |e| = r therefore leaves the
    passive coordinates uncertain by sqrt(r / s_max) and cannot tell s_min from zero once s_min is
    below sqrt(r s_max) (same units as the rows: m for position rows). Newton converges only linearly
    at a singular point, so there it stops near its tolerance (`CLOSURE_TOL`), while at a regular pose
    it overshoots to rounding; r is floored at rounding, eps s_max. Measured on the five-bar with its
    distal links collinear (tests/test_bad_inputs_singular.py): at the singular input s_min is 0.6 to
    0.9 sqrt(r s_max); 1e-8 rad away it is over 30 times that. `SINGULAR_MARGIN` (3, ours) sits above
    the singular floor.

    Args:
        s_max: largest singular value of the passive block (the rows' scale).
        residual: closure residual norm reached at the configuration.
    """
    floor = float(np.finfo(float).eps) * s_max
    return SINGULAR_MARGIN * float(np.sqrt(max(residual, floor) * s_max))


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
    cond = _condition(s, independent_rows)
    k = min(independent_rows, s.size)
    if k == 0:
        return cond
    limit = resolvable_singular_value(s[0], residual)
    if s[k - 1] <= 0 or (s[k - 1] < limit and not allow_singular):
        raise SingularConfiguration(cond, f"passive block of the closure Jacobian: smallest singular value {s[k - 1]:.2e} "
                                    f"below the {limit:.2e} a closure residual of {residual:.1e} resolves "
                                    "(inputs do not determine the motion)")
    return cond


def check_regular(rows: ClosureRows, data: pin.Data, q: np.ndarray, free_v: np.ndarray, independent_rows: int) -> None:
    """Raise `SingularConfiguration` where the inputs (all but `free_v`) do not determine the motion at q
    (or at any sample of a (N, nq) q), to what the closure resolves (`judge_passive`)."""
    for qi in np.atleast_2d(q):
        update_kinematics(rows.model, data, qi)
        s = np.linalg.svd(rows.jacobian(data)[:, free_v], compute_uv=False)
        judge_passive(s, independent_rows, float(np.linalg.norm(rows.residual(data))))


class Conditioned(np.ndarray):
    """A kinematic result (velocities or accelerations) with the condition number of the passive block
    it was solved with (`condition`, s_max / s_min on the generic rank; nan on derived arrays)."""

    condition: float = float("nan")


def _condition(s: np.ndarray, independent_rows: int) -> float:
    k = min(independent_rows, s.size)
    if k == 0:
        return 1.0
    return float(s[0] / s[k - 1]) if s[k - 1] > 0 else float("inf")


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
    if free_v.size > independent_rows:
        raise SingularConfiguration(float("inf"), f"{free_v.size} free coordinates but only {independent_rows} independent "
                                    "closure rows: the inputs do not determine the motion (give more inputs)")
    U, s, Vt = np.linalg.svd(J[:, free_v], full_matrices=False)
    cond = judge_passive(s, independent_rows, residual, allow_singular)
    k = min(independent_rows, s.size)
    b = J[:, input_v] @ v_inputs
    if rhs is not None:
        b = b + rhs
    x = np.zeros(J.shape[1])
    x[input_v] = v_inputs
    # truncated to the generic rank: a row redundant at a regular pose stays redundant here, even
    # when rounding leaves it a singular value just above any fixed threshold
    x[free_v] = -Vt[:k].T @ ((U[:, :k].T @ b) / s[:k])
    out = x.view(Conditioned)
    out.condition = cond
    return out
