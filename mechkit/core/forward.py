"""Constrained forward dynamics: accelerations under joint efforts, M a + nle = tau + J^T lambda,
J a + gamma = 0, by four methods with tolerances relative to the model.

- "proximal": Pinocchio's proximal `constraintDynamics` on the equivalent legacy constraint models
  (mu and accuracy relative to the Delassus scale; `mechkit.core.pin_constraints`);
- "lcaba": Pinocchio's loop-constrained articulated-body algorithm on the same models (an augmented
  Lagrangian of O(n) sweeps: the method for many loops);
- "kkt": a dense KKT solve on independent closure rows of mechkit's kernel, equilibrated before the LU;
- "nullspace": the exact reference: the accelerations that satisfy every row, a = a_p + N z, with N a
  basis of the null space of J and the reduced mass matrix N^T M N; N from one LU of a square block of
  J where bounds certify the rank and the consistency the SVD would decide (the method for many
  loops), else from the SVD (`mechkit.core.null_space`); first, that LU without the rank bound, its answer
  kept where it passes the other tests and closes every row (`mechkit.core.dense_forward`).

Every result is checked against J a + gamma = 0 on the rows its method solved: a violation beyond
`ACCELERATION_TOL` is an error (`ConstraintViolated`), never a return value, and a state whose gamma
leaves the range of J (no acceleration satisfies every row: a velocity along a freedom that exists
only instantaneously) is refused by every method (`InconsistentMotion`).
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from math import dist, hypot, inf, isfinite, sqrt

import numpy as np
import pinocchio as pin
import scipy.linalg
import scipy.linalg.blas
import scipy.linalg.lapack

from mechkit.base.exceptions import ConstraintViolated, InconsistentMotion, SingularConfiguration
from mechkit.core import dense_forward, rank
from mechkit.core.model import ClosureData, ClosureModel
from mechkit.core.null_space import null_space
from mechkit.core.pin_constraints import LegacyConstraints, expresses, proximal_settings
from mechkit.core.results import ForwardDynamicsResult

#: Methods of `forward_dynamics`.
METHODS = ("proximal", "lcaba", "kkt", "nullspace")
#: Default (mu, accuracy, max_iter) of Pinocchio's methods: mu relative to the Delassus scale
#: (`ClosureModel.delassus_scale`), accuracy in m/s^2 for position rows (ours; measured: lcaba at mu = 1
#: agrees with the dense KKT to 3e-11 on the planar mechanisms and the ladder of 64 loops).
DEFAULTS = {"proximal": (1e-11, 1e-12, 20), "lcaba": (1.0, 1e-10, 200)}
#: lcaba's step criterion is given accuracy / (max |J_i| times a margin) (ours): the rows' lever at the
#: neutral configuration only approximates the one at the state, and its final error is checked against
#: `accuracy`; a result that fails the check is solved again at the next, tighter margin. Measured: the
#: first margin certifies the ladder of 64 loops in 31 iterations (the second alone takes 126); both
#: together certify 49 of the bench's 64 states of the registered mechanisms, as the second alone does
#: (the first alone 33), within 2e-10 of the exact null-space solve (the tetrahedral unit: 1.2e-7).
LCABA_STEP_MARGINS = (1.0, 10.0)
#: Smallest LU pivot of the equilibrated KKT matrix, relative to the largest, of a regular system.
PIVOT_TOL = 1e-14
#: Largest |J a + gamma| of a result, relative to max|J_i| max|a| + max|gamma| (ours).
ACCELERATION_TOL = 1e-8


def check_acceleration(
    J: np.ndarray,
    a: np.ndarray,
    gamma: np.ndarray,
    what: str,
    a_scale: Callable[[], float] | None = None,
    drift: float = 0.0,
    solved: np.ndarray | None = None,
) -> None:
    """Refuse accelerations that violate J a + gamma = 0 beyond `ACCELERATION_TOL` relative to the terms.

    Past that, gamma's part outside the range of J (which no acceleration cancels) is judged against
    `rank.range_limit` (rounding, plus a redundant row's share of the state's drift off the manifold),
    and the residual against the tolerance on what remains: its part in the range of J, or its value on
    the independent rows the method solved.

    Args:
        J: (rows, nv) the rows the method solved.
        a: (nv,) the accelerations (rad/s^2 or m/s^2).
        gamma: (rows,) their drift (J a + gamma = 0 on the constraint manifold).
        what: the method, for the error.
        a_scale: gives the size of the accelerations the loads would cause unconstrained (rad/s^2 or
            m/s^2): where the closures hold the mechanism still, a is rounding and this sets the scale
            (called only when the tests without it fail).
        drift: the state's closure residual over the rows' lever arm (dimensionless, `rank.range_limit`).
        solved: indices of the independent rows the method solved exactly (None: judged on every row).

    Raises:
        SingularConfiguration: a not finite.
        InconsistentMotion: gamma leaves the range of J beyond `rank.range_limit` (no rigid answer).
        ConstraintViolated: max |J a + gamma| above the tolerance.
    """
    rows = J.shape[0]
    if rows and _closes(J, a, -gamma):
        return
    if not np.isfinite(a).all():
        raise SingularConfiguration(float("inf"), f"{what} returned non-finite accelerations")
    if not rows:
        return
    r = J.dot(a) + gamma
    residual, g = float(np.abs(r).max()), float(np.abs(gamma).max())
    if residual <= ACCELERATION_TOL * g:  # below a part of the limit: the rest need not be computed
        return
    c = sqrt(float(np.einsum("ij,ij->i", J, J).max()))
    limit = ACCELERATION_TOL * (c * float(np.abs(a).max(initial=0.0)) + g)
    if residual <= limit:
        return
    U, s, _ = np.linalg.svd(J, full_matrices=True)
    # off the manifold by d a redundant row's singular value rises to O(d sigma_1): not resolved below it
    U0 = U[:, int(np.sum(s > max(rank.RANK_TOL, drift) * max(s[0], 1e-290))) :]
    delta, gn = float(np.linalg.norm(U0.T @ gamma)), float(np.linalg.norm(gamma))
    allowed = rank.range_limit(max(gn, c * float(np.linalg.norm(a))), gn, drift)
    if delta > allowed:
        raise InconsistentMotion(
            delta,
            allowed,
            f"{what}: the closure drift gamma leaves the range of J "
            "(the velocity moves along a freedom that exists only instantaneously)",
        )
    residual = float(np.abs(r - U0 @ (U0.T @ r)).max())  # the part in the range of J
    if solved is not None and U0.shape[1]:
        residual = min(residual, float(np.abs(r[solved]).max(initial=0.0)))
    if a_scale is not None:
        limit += ACCELERATION_TOL * c * a_scale()
    if not residual <= limit:
        raise ConstraintViolated(residual, limit, what)


def _closes(J: np.ndarray, a: np.ndarray, target: np.ndarray) -> bool:
    """Whether max |J a - target| <= `ACCELERATION_TOL` (max_i |J_i| max |a| + max |target|) as norms show
    it, |J a - target| <= TOL |target| / sqrt(rows) or TOL |J|_F |a| / sqrt(rows nv) (J (rows, nv), a (nv,),
    target (rows,); NaN or inf fails both): the check's common case, in Python floats (no numpy per-op cost)."""
    t = target.tolist()
    residual = dist(J.dot(a).tolist(), t) * sqrt(len(t))
    if residual <= ACCELERATION_TOL * hypot(*t) < inf:
        return True
    bound = ACCELERATION_TOL * sqrt(rank.squared_norm(J)) * hypot(*a.tolist())  # inf where it overflows
    return residual * sqrt(len(a)) <= bound < inf


def _unconstrained_scale(cm: ClosureModel, data: pin.Data, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> float:
    """max |tau - nle| / M_jj: the accelerations the loads would cause with no closure (rad/s^2 or m/s^2)."""
    loads = np.abs(tau - pin.rnea(cm.model, data, q, v, np.zeros(cm.nv)))
    return float(np.max(loads / np.diag(pin.crba(cm.model, data, q))))


def pinocchio_methods_apply(cm: ClosureModel) -> bool:
    """Whether "proximal" and "lcaba" (Pinocchio's legacy constraint models) can run on this model.

    Args:
        cm: the closure model.

    Returns:
        False where a coupling row or a Hooke or prismatic cut has no legacy model ("kkt" and
        "nullspace" solve every model).
    """
    return expresses(list(cm.kernel.cuts), len(cm.kernel.couplings))


def _legacy(cm: ClosureModel, cd: ClosureData, ordered: bool = False) -> LegacyConstraints:
    """The data's legacy constraints for "proximal" (or, `ordered`, for "lcaba": each its own Pinocchio data)."""
    key = "lcaba" if ordered else "proximal"
    if key not in cd.legacy:
        cd.legacy[key] = LegacyConstraints(cm.model, list(cm.kernel.cuts), len(cm.kernel.couplings), ordered)
    return cd.legacy[key]


def _settings(
    cm: ClosureModel,
    cd: ClosureData,
    method: str,
    mu: float | None,
    accuracy: float | None,
    max_iter: int | None,
    margin: float = 1.0,
):
    """Pinocchio's proximal settings of a method, made once per (method, mu, accuracy, max_iter, margin)
    (None: `DEFAULTS`; the defaults kept under the method's name): mu in units of the Delassus scale; the
    accuracy divided by it ("proximal": Pinocchio tests its iterations on the multipliers) or by the rows'
    lever arm and the step margin ("lcaba": it tests J delta a; see `LCABA_STEP_MARGINS`)."""
    key = (method, mu, accuracy, max_iter, margin)
    key = method if key[1:] == (None, None, None, 1.0) else key
    prox = cd.settings.get(key)
    if prox is None:
        mu, accuracy, max_iter = (d if x is None else x for x, d in zip((mu, accuracy, max_iter), DEFAULTS[method]))
        divisor = cm.delassus_scale if method == "proximal" else margin * max(cm.row_scale, 1.0)
        prox = cd.settings[key] = proximal_settings(accuracy / divisor, mu * cm.delassus_scale, max_iter)
    return prox


def _proximal(cm, cd, q, v, tau, mu, accuracy, max_iter, baumgarte) -> ForwardDynamicsResult:
    """Pinocchio's proximal constraintDynamics, checked on the anchors' rows it solved (their Jacobian at
    the state and the right-hand side -gamma it left); the constraint force J^T lambda from its multipliers."""
    legacy = cd.legacy.get("proximal") or _legacy(cm, cd)
    if baumgarte is not None or legacy.stabilised:
        legacy.set_baumgarte(baumgarte)
    default = mu is None and accuracy is None and max_iter is None
    settings = (default and cd.settings.get("proximal")) or _settings(cm, cd, "proximal", mu, accuracy, max_iter)
    a, lam, J, rhs = legacy.dynamics(q, v, tau, settings)  # rhs = -gamma
    if not _closes(J, a, rhs):
        if not isfinite(a @ a):  # a NaN or inf state: refused before the drift is computed from it
            raise SingularConfiguration(inf, "forward dynamics (proximal) returned non-finite accelerations")
        drift = _rows_and_drift(cm, cd, q, v, None)[2]  # mechkit's rows: cd.pin, not the legacy data
        scale = partial(_unconstrained_scale, cm, cd.pin, q, v, tau)  # not a lambda: no closure cells in the call
        check_acceleration(J, a, -rhs, "forward dynamics (proximal)", scale, drift)
    return ForwardDynamicsResult(a, None, settings.iter, (J, lam))


def _lcaba(cm, cd, q, v, tau, mu, accuracy, max_iter) -> ForwardDynamicsResult:
    """lcaba stops when the closure error, or else the last step |delta a|, falls below its one accuracy;
    it is given accuracy / (max |J_i| times a margin) (`_settings`), so that a step stop leaves J delta a
    within about `accuracy`; the final error (before the last step, plus J times that step) is checked
    against it, and a failed check solves again at the next margin of `LCABA_STEP_MARGINS`."""
    mu, accuracy, max_iter = (d if x is None else x for x, d in zip((mu, accuracy, max_iter), DEFAULTS["lcaba"]))
    if mu <= 0:
        raise SingularConfiguration(float("inf"), "lcaba needs a positive mu (its penalty is 1 / mu)")
    legacy = _legacy(cm, cd, ordered=True)
    for margin in LCABA_STEP_MARGINS:
        prox = _settings(cm, cd, "lcaba", mu, accuracy, max_iter, margin)
        a = legacy.loop_constrained_aba(q, v, tau, prox).copy()
        if not isfinite(a @ a):
            raise SingularConfiguration(float("inf"), "pin.lcaba returned non-finite accelerations")
        J = legacy.jacobian()
        residual = float(np.max(np.abs(legacy.lcaba_error() + J @ legacy.last_step()), initial=0.0))
        if residual <= accuracy:
            return ForwardDynamicsResult(a, pin.rnea(cm.model, legacy.data, q, v, a) - tau, prox.iter)
    raise ConstraintViolated(residual, accuracy, f"pin.lcaba after {prox.iter} iterations")


def _rows_and_drift(
    cm: ClosureModel, cd: ClosureData, q: np.ndarray, v: np.ndarray, baumgarte: tuple[float, float] | None
) -> tuple[np.ndarray, np.ndarray, float]:
    """mechkit's closure Jacobian (rows, nv) and drift (rows,) at (q, v), Baumgarte terms added (one
    Pinocchio pass, read as views: call before any other pass), and the state's relative distance from
    the constraint manifold, (max |e| + max |J v| / max |v|) over the rows' lever arm
    `ClosureModel.row_scale` (for `rank.range_limit`: an integrator's stage lies off the manifold)."""
    pin.computeJointJacobiansTimeVariation(cm.model, cd.pin, q, v)
    k, Jw, G = cm.kernel, cd.J, cd.used_placements()
    world = k.world(G)
    e, J, W = k.rows(world, Jw, q)
    gamma = k.drift(G, k.twists(Jw, v), k.twists(cd.dJ, v), q, v, world, W)
    if baumgarte is not None:
        kp, kd = baumgarte
        gamma = gamma + kd * (J @ v) + kp * e
    v_max = float(np.abs(v).max(initial=0.0))
    off = float(np.abs(J.dot(v)).max(initial=0.0)) / v_max if v_max > 0 else 0.0
    return J, gamma, (float(np.abs(e).max(initial=0.0)) + off) / cm.row_scale


def _power_of_two(x: float) -> float:
    """x rounded to a power of two; 1 within a factor 16 of 1 (a model near unit scale solves unscaled)."""
    return 1.0 if 1 / 16 <= x <= 16 else float(2.0 ** np.round(np.log2(x)))


def _mass_matrix(cm: ClosureModel, data: pin.Data, q: np.ndarray) -> np.ndarray:
    """The joint-space mass matrix at q as Pinocchio's crba fills it: its upper triangle (the lower one is
    not read: BLAS symmetric products, or `np.triu`). A coordinate without inertia (a massless link's) is
    allowed: whether the closures fix its motion is decided by the solve (the KKT pivots, N^T M N).

    Raises:
        SingularConfiguration: a negative or non-finite diagonal, or a non-finite entry.
    """
    M = pin.crba(cm.model, data, q)
    if not (M.diagonal().min() >= 0 and np.isfinite(M).all()):
        raise SingularConfiguration(float("inf"), "mass matrix: a negative or non-finite inertia")
    return M


def _kkt(cm, cd, q, v, tau, baumgarte) -> ForwardDynamicsResult:
    """Dense KKT on independent rows (cached in the data; chosen again where they lose rank),
    equilibrated by powers of two (mass block to a largest diagonal near 1, rows to a largest norm near
    1), so the pivot test is relative to the model's own scale."""
    J, gamma, drift = _rows_and_drift(cm, cd, q, v, baumgarte)
    M = _mass_matrix(cm, cd.pin, q)
    M = np.triu(M) + np.triu(M, 1).T
    nle = pin.nonLinearEffects(cm.model, cd.pin, q, v)
    for rows in ([cd.kkt_rows] if cd.kkt_rows is not None else []) + [None]:
        rows = rank.independent_rows(J) if rows is None else rows
        Ji, gi = J[rows], gamma[rows]
        n, m = cm.nv, len(rows)
        inertias = np.diag(M)
        d = np.full(n, _power_of_two(float(1.0 / np.sqrt(np.max(inertias, initial=0.0) or 1.0))))
        JD = Ji * d
        r = np.full(m, _power_of_two(1.0 / max(float(np.max(np.linalg.norm(JD, axis=1), initial=0.0)), 1e-300)))
        K = np.zeros((n + m, n + m))
        K[:n, :n], K[:n, n:], K[n:, :n] = d[:, None] * M * d, -(r[:, None] * JD).T, r[:, None] * JD
        lu, piv, _ = scipy.linalg.lapack.dgetrf(K)  # an exactly zero pivot is judged below, not warned about
        pivots = np.abs(np.diag(lu))
        if np.min(pivots, initial=np.inf) >= PIVOT_TOL * np.max(pivots, initial=0.0):
            cd.kkt_rows = rows
            break
    else:
        raise SingularConfiguration(
            float(np.linalg.cond(K)),
            "KKT matrix (equilibrated): dependent constraint rows or a coordinate without inertia",
        )
    x = scipy.linalg.lapack.dgetrs(lu, piv, np.concatenate([d * (tau - nle), -r * gi]))[0]
    a, lam = d * x[:n], r * x[n:]
    check_acceleration(
        J, a, gamma, "forward dynamics (KKT)", lambda: float(np.max(np.abs(d * d * (tau - nle)))), drift, rows
    )
    return ForwardDynamicsResult(a, Ji.T @ lam)


def _nullspace(cm, cd, q, v, tau, baumgarte) -> ForwardDynamicsResult:
    """a = a_p + N z, N a basis of the null space of J, N^T M N the reduced mass matrix: `dense_forward`'s solve where
    it closes every row, else N from a partition of J whose bounds certify the SVD's decisions, else the SVD."""
    (J, gamma, drift), M = _rows_and_drift(cm, cd, q, v, baumgarte), _mass_matrix(cm, cd.pin, q)  # rows first
    nle, blas = pin.nonLinearEffects(cm.model, cd.pin, q, v), scipy.linalg.blas
    if (a := dense_forward.solve(cd, J, gamma, drift, M, tau - nle, ACCELERATION_TOL)) is not None:
        return ForwardDynamicsResult(a, blas.dsymv(1.0, M, a) + nle - tau)
    a_p, N = null_space(cd, J, gamma, drift)
    _, z, info = scipy.linalg.lapack.dposv(N.T.dot(blas.dsymm(1.0, M, N)), N.T.dot(tau - nle - blas.dsymv(1.0, M, a_p)))
    if info:
        raise SingularConfiguration(float("inf"), "reduced mass matrix N^T M N: a free motion carries no inertia")
    a, solved = a_p + N.dot(z), cd.partition[0] if cd.partition is not None else None
    check_acceleration(J, a, gamma, "forward dynamics (null space)", drift=drift, solved=solved)
    return ForwardDynamicsResult(a, blas.dsymv(1.0, M, a) + nle - tau)


def forward_dynamics(
    cm: ClosureModel,
    cd: ClosureData,
    q: np.ndarray,
    v: np.ndarray,
    tau: np.ndarray,
    method: str = "proximal",
    *,
    mu: float | None = None,
    accuracy: float | None = None,
    max_iter: int | None = None,
    baumgarte: tuple[float, float] | None = None,
) -> ForwardDynamicsResult:
    """Accelerations of one state under joint efforts.

    Args:
        cm: the closure model.
        cd: its data (workspace; caches rows, partitions and Pinocchio's constraint models).
        q: (nq,) configuration.
        v: (nv,) velocity.
        tau: (nv,) joint efforts (N m or N).
        method: one of `METHODS` (see the module docstring).
        mu: proximal parameter of "proximal" and "lcaba", relative to `ClosureModel.delassus_scale`
            (None: `DEFAULTS`).
        accuracy: stopping accuracy of "proximal" and "lcaba", in m/s^2 for position rows (None: `DEFAULTS`).
        max_iter: iteration cap of "proximal" and "lcaba" (None: `DEFAULTS`).
        baumgarte: (Kp (1/s^2), Kd (1/s)) closure stabilisation, J a + gamma + Kd J v + Kp e = 0
            (not for "lcaba").

    Returns:
        The accelerations a (nv,), the generalised constraint force J^T lambda (nv,) and the
        iterations of Pinocchio's solver (0 for "kkt" and "nullspace").

    Raises:
        SingularConfiguration: accelerations not unique or not finite.
        ConstraintViolated: the result violates J a + gamma = 0 on the rows its method solved.
        InconsistentMotion: gamma leaves the range of J: no rigid answer at this state.
        MethodUnavailable: a cut or coupling Pinocchio's constraint models cannot express ("proximal", "lcaba").
    """
    if method == "proximal":
        return _proximal(cm, cd, q, v, tau, mu, accuracy, max_iter, baumgarte)
    if method == "lcaba":
        return _lcaba(cm, cd, q, v, tau, mu, accuracy, max_iter)
    if method == "kkt":
        return _kkt(cm, cd, q, v, tau, baumgarte)
    return _nullspace(cm, cd, q, v, tau, baumgarte)


def forward_dynamics_batch(
    cm: ClosureModel,
    cd: ClosureData,
    Q: np.ndarray,
    V: np.ndarray,
    T: np.ndarray,
    method: str = "proximal",
    **settings: float | tuple | None,
) -> ForwardDynamicsResult:
    """`forward_dynamics` of N states.

    Args:
        cm: the closure model.
        cd: its data (workspace).
        Q: (N, nq) configurations.
        V: (N, nv) velocities.
        T: (N, nv) joint efforts (N m or N).
        method: one of `METHODS`.
        **settings: keyword settings of `forward_dynamics` (mu, accuracy, max_iter, baumgarte).

    Returns:
        Accelerations (N, nv), generalised constraint forces (N, nv) and the largest iteration count.
    """
    out = [forward_dynamics(cm, cd, q, v, t, method, **settings) for q, v, t in zip(Q, V, T)]
    return ForwardDynamicsResult(
        np.array([r.a for r in out]).reshape(len(Q), cm.nv),
        np.array([r.constraint_force for r in out]).reshape(len(Q), cm.nv),
        max((r.iterations for r in out), default=0),
    )
