"""Constrained forward dynamics (constrained ABA) with tolerances relative to the model.

Two methods: Pinocchio's proximal `constraintDynamics` on the equivalent `RigidConstraintModel`s
(mu and accuracy relative to the Delassus scale), and a dense KKT solve on independent rows,
equilibrated before the LU. A result that violates J a + gamma = 0 beyond `ACCELERATION_TOL` is an
error, never returned. Bodies too light for Pinocchio's inertia arithmetic are refused.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pinocchio as pin
import scipy.linalg

from mechkit.base.exceptions import ClosureNotConverged, InvalidParameters, SingularConfiguration
from mechkit.core.closures import ClosureRows, rigid_constraint_models
from mechkit.core.dynamics import ForwardDynamicsResult, independent_rows

#: Methods of `Mechanism.forward_dynamics`.
METHODS = ("proximal", "kkt")
#: Lightest body (kg): Pinocchio's inertia sums are exact above its epsilon (2.2e-16 kg); ours, with a margin.
MIN_BODY_MASS = 1e-14
#: Smallest LU pivot of the equilibrated KKT matrix, relative to the largest, of a regular system.
PIVOT_TOL = 1e-14
#: Allowance, in units of the state's own second-order inconsistency, for a result on such a state (ours).
INCONSISTENT_FACTOR = 20.0
#: Largest |J a + gamma| of a forward-dynamics result, relative to max|J_i| max|a| + max|gamma| (ours).
ACCELERATION_TOL = 1e-8


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
    scale = float(np.max(np.sum(J ** 2, axis=1)) / np.max(np.diag(M)))
    return scale if scale > 0 else 1.0  # rows all zero here: nothing to scale against


def check_closure_acceleration(J: np.ndarray, a: np.ndarray, gamma: np.ndarray, slack: float = 0.0,
                               what: str = "forward dynamics", a_scale: Callable[[], float] | None = None) -> None:
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
        a_scale: gives the size of the accelerations the loads would cause unconstrained (rad/s^2 or
            m/s^2), max |tau - nle| / M_jj: where the closures hold the mechanism still, a is rounding
            and this sets the scale (called only when the tests without it fail).

    Raises:
        ClosureNotConverged: max |J a + gamma| above ACCELERATION_TOL (max |J_i| max |a| + max |gamma|)
            + slack (+ INCONSISTENT_FACTOR delta).
    """
    if J.shape[0] == 0:
        return
    r = J @ a
    r += gamma
    residual = float(np.abs(r).max())
    g = float(np.abs(gamma).max())
    if residual <= ACCELERATION_TOL * g + slack:  # below a part of the limit: the rest need not be computed
        return
    c = math.sqrt(float(np.einsum("ij,ij->i", J, J).max()))
    limit = ACCELERATION_TOL * (c * float(np.abs(a).max(initial=0.0)) + g) + slack
    if residual <= limit:
        return
    # least squares by complete orthogonal factorisation (LAPACK gelsy, 3-4 times faster than numpy's SVD-based
    # gelsd on the deployable's 72 x 66 rows), rank cut at numpy's default eps max(rows, nv)
    x = scipy.linalg.lstsq(J, -gamma, cond=np.finfo(float).eps * max(J.shape), lapack_driver="gelsy")[0]
    limit += INCONSISTENT_FACTOR * float(np.abs(J @ x + gamma).max())
    if residual <= limit:
        return
    if a_scale is not None:
        limit += ACCELERATION_TOL * c * a_scale()
    if not residual <= limit:
        raise ClosureNotConverged(residual, limit, 1, f"{what}: the accelerations violate J a + gamma = 0")


def plain_state(q: Any, v: Any, tau: Any, nq: int, nv: int) -> bool:
    """True for the common call that needs no conversion: float64 arrays of shapes (nq,), (nv,), (nv,),
    all finite. Anything else (lists, other dtypes, batches, NaN or inf) goes through
    `arguments.state`, which converts it or names what is wrong."""
    return (isinstance(q, np.ndarray) and isinstance(v, np.ndarray) and isinstance(tau, np.ndarray)
            and q.dtype == np.float64 and v.dtype == np.float64 and tau.dtype == np.float64
            and q.shape == (nq,) and v.shape == (nv,) and tau.shape == (nv,)
            and bool(np.isfinite(q).all() and np.isfinite(v).all() and np.isfinite(tau).all()))


def _power_of_two(x: float) -> float:
    """x rounded to a power of two; 1 within a factor 16 of 1 (a model near unit scale solves unscaled)."""
    return 1.0 if 1 / 16 <= x <= 16 else float(2.0 ** np.round(np.log2(x)))


def kkt_forward(model: pin.Model, data: pin.Data, q: np.ndarray, v: np.ndarray, tau: np.ndarray, J: np.ndarray, gamma: np.ndarray,
                rows: np.ndarray | None = None) -> ForwardDynamicsResult:
    """Dense KKT solve on independent rows of J (needs J, gamma at (q, v)).

    The system is equilibrated before the LU (mass-matrix block to a largest diagonal near 1, rows of J
    to a largest norm near 1, by powers of two), so the pivot test is relative to the model's own
    scale: a model of 1e30 kg or of millimetre links solves like one of kilograms and metres.

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
    # one power-of-two scale per block, exact in floating point, and none near unit scale: the LU's
    # pivot order, hence its rounding, then stays that of the unscaled system (rescaling cost the
    # ill-conditioned deployable 12 to 20 times in its inverse-forward round trip)
    d = np.full(n, _power_of_two(np.min(mass_scaling(M))))
    JD = Ji * d
    r = np.full(m, _power_of_two(1.0 / max(float(np.max(np.linalg.norm(JD, axis=1), initial=0.0)), 1e-300)))
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
    check_closure_acceleration(Ji, a, gi, what="forward dynamics (KKT)", a_scale=lambda: float(np.max(np.abs(d * d * (tau - nle)))))
    return ForwardDynamicsResult(a, Ji.T @ lam)


def constraint_models(model: pin.Model, cuts: list) -> tuple[tuple[Any, Any], pin.Data]:
    """Pinocchio `RigidConstraintModel`s and datas equivalent to the cuts, and the data initialised for them."""
    cms = pin.StdVec_RigidConstraintModel()
    for cm in rigid_constraint_models(model, cuts):
        cms.append(cm)
    cds = pin.StdVec_RigidConstraintData()
    for cm in cms:
        cds.append(cm.createData())
    data = model.createData()
    pin.initConstraintDynamics(model, data, cms, cds)
    return (cms, cds), data


def set_baumgarte(cms: Any, baumgarte: tuple[float, float] | None, current: tuple[float, float]) -> tuple[float, float]:
    """Set (Kp, Kd) on every constraint model when they differ from `current`; returns the gains now set."""
    gains = (0.0, 0.0) if baumgarte is None else tuple(baumgarte)
    if gains != current:
        for cm in cms:
            cm.setBaumgarteCorrectorParameters(pin.BaumgarteCorrectorParameters(*gains))
    return gains


def proximal_forward(model: pin.Model, pin_data: pin.Data, data: pin.Data, constraints: tuple,
                     q: np.ndarray, v: np.ndarray, tau: np.ndarray, prox: pin.ProximalSettings) -> ForwardDynamicsResult:
    """`pin.constraintDynamics` with its result checked on the rows it solved.

    The check is on Pinocchio's own constraint Jacobian and right-hand side at (q, v), both left by
    the call (`getConstraintsJacobian`, `primal_rhs_contact` = -(gamma + Baumgarte terms), in each
    anchor's c1 frame): J a + gamma = 0 on the system actually solved, valid on and off the closure
    manifold (on it, these rows span the same constraint as `mechkit.core.closures`' rows).

    Args:
        pin_data: the data the constraints were initialised with; data: a scratch data (only for the
            unconstrained-acceleration scale of a failing check).
        constraints: (RigidConstraintModels, RigidConstraintDatas), Baumgarte gains already set.
        prox: Pinocchio's proximal settings, already scaled to the model (`ForwardSolver.settings`).

    Raises:
        SingularConfiguration: non-finite accelerations.
        ClosureNotConverged: J a + gamma = 0 violated beyond `check_closure_acceleration`'s tolerance.
    """
    cms, cds = constraints
    a = pin.constraintDynamics(model, pin_data, q, v, tau, cms, cds, prox).copy()
    if not np.isfinite(a).all():
        raise SingularConfiguration(float("inf"), f"pin.constraintDynamics returned non-finite accelerations (mu={prox.mu})")
    J = pin.getConstraintsJacobian(model, pin_data, cms, cds)
    gamma = -pin_data.primal_rhs_contact[:J.shape[0]]

    def a_scale() -> float:
        loads = np.abs(tau - pin.rnea(model, data, q, v, np.zeros(model.nv)))
        return float(np.max(loads / np.diag(pin.crba(model, data, q))))

    check_closure_acceleration(J, a, gamma, 0.0, "forward dynamics (proximal)", a_scale)
    return ForwardDynamicsResult(a, pin.rnea(model, pin_data, q, v, a) - tau)


class ForwardSolver:
    """One mechanism's forward dynamics, with what it caches: Pinocchio's constraint models, the KKT rows
    and the Delassus scale (both at the home assembly), the Baumgarte gains set on the models.

    Args:
        model: the tree's Pinocchio model; data: a scratch data of it.
        rows: the closure rows; cuts: their cuts (for Pinocchio's constraint models).
        home_q: the home assembly (nq,).
    """

    def __init__(self, model: pin.Model, data: pin.Data, rows: ClosureRows, cuts: list, home_q: np.ndarray):
        self.model, self.data, self.rows, self.cuts, self.home_q = model, data, rows, cuts, home_q
        self._constraints: tuple | None = None
        self._gains = (0.0, 0.0)
        self._kkt_rows: np.ndarray | None = None
        self._delassus: float | None = None
        self._settings: dict = {}

    def constraints(self) -> tuple[Any, Any]:
        """Pinocchio `RigidConstraintModel`s (and datas) equivalent to the closures (built once)."""
        if self._constraints is None:
            self._constraints, self.pin_data = constraint_models(self.model, self.cuts)
        return self._constraints

    def settings(self, mu: float, accuracy: float, max_iter: int) -> pin.ProximalSettings:
        """Pinocchio's proximal settings for mu (in units of the Delassus scale at home, `delassus_scale`)
        and accuracy (m/s^2 for position rows; Pinocchio tests its iterations on the multipliers, so it
        is given accuracy / scale), built once per (mu, accuracy, max_iter)."""
        prox = self._settings.get((mu, accuracy, max_iter))
        if prox is None:
            if self._delassus is None:
                self._delassus = delassus_scale(pin.crba(self.model, self.data, self.home_q), self._jacobian(self.home_q))
            prox = self._settings[(mu, accuracy, max_iter)] = pin.ProximalSettings(
                accuracy / self._delassus, mu * self._delassus, max_iter)
        return prox

    def _jacobian(self, q: np.ndarray) -> np.ndarray:
        pin.computeJointJacobians(self.model, self.data, q)
        pin.updateFramePlacements(self.model, self.data)
        return self.rows.jacobian(self.data)

    def solve(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray, method: str, *, mu: float, accuracy: float,
              max_iter: int, baumgarte: tuple[float, float] | None) -> ForwardDynamicsResult:
        """Accelerations under efforts tau by `method` ("proximal" or "kkt"; see `Mechanism.forward_dynamics`)."""
        if method == "proximal":
            cms, cds = self.constraints()
            self._gains = set_baumgarte(cms, baumgarte, self._gains)
            return proximal_forward(self.model, self.pin_data, self.data, (cms, cds), q, v, tau,
                                    self.settings(mu, accuracy, max_iter))
        if self._kkt_rows is None:
            self._kkt_rows = independent_rows(self._jacobian(self.home_q))
        J = self._jacobian(q)
        residual = self.rows.residual(self.data)
        pin.forwardKinematics(self.model, self.data, q, v, np.zeros(self.model.nv))
        pin.updateFramePlacements(self.model, self.data)
        gamma = self.rows.drift(self.data)
        if baumgarte is not None:
            kp, kd = baumgarte
            gamma = gamma + kd * (J @ v) + kp * residual
        try:
            return kkt_forward(self.model, self.data, q, v, tau, J, gamma, self._kkt_rows)
        except SingularConfiguration:  # the cached rows lost rank here: choose rows at this q
            return kkt_forward(self.model, self.data, q, v, tau, J, gamma)
