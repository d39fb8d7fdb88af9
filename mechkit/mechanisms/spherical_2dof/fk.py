"""Forward kinematics of the 2-DOF spherical platform three ways, and where each one fails.

Methods, all from a start attitude phi0 and the motor angles theta_d: ``paper`` (`fk_paper`: the
paper's iteration, Newton on the closed-form IK), ``newton`` (`fk_newton`: Newton on the constraints
(7)), ``closure`` (the core's closure solver on the Pinocchio tree, started from the tree pose
nearest to phi0 with the motors at theta_d).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from mechkit.base.exceptions import ClosureNotConverged, InvalidParameters, SingularConfiguration
from mechkit.mechanisms.spherical_2dof import kinematics as kin
from mechkit.mechanisms.spherical_2dof.joint_state import tree_q
from mechkit.mechanisms.spherical_2dof.kinematics import BRANCHES
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = [
    "METHODS",
    "NEAR_SINGULAR",
    "REGULAR",
    "BasinRow",
    "FKResult",
    "basin_study",
    "fk_closure",
    "fk_newton",
    "fk_paper",
    "solve_fk",
]


@dataclass(frozen=True)
class FKResult:
    """A forward-kinematics solve.

    Attributes:
        phi: (roll, pitch), rad.
        iterations: steps taken.
        step: norm of the last step, rad.
    """

    phi: np.ndarray
    iterations: int
    step: float


def fk_paper(
    p: kin.Geometry,
    theta_d: Sequence[float],
    phi0: Sequence[float],
    branches: Sequence[int] = BRANCHES,
    tol: float = 1e-13,
    max_iter: int = 50,
) -> FKResult:
    """The paper's iterative forward kinematics (section 2.3.2).

    ``theta_k = InvKin(P_k)``, ``S_k = J(theta_k, P_k) (theta_d - theta_k)``, ``P_k+1 = P_k + S_k`` until
    ``|S_k| <= tol``. The paper prints ``S_k = -J^-1(theta_k) Delta theta_k``; with its own
    ``phi' = J theta'`` (eq. 11) the step that makes ``InvKin(P_k+1) = theta_d`` to first order is
    ``J Delta theta``: a Newton iteration on the closed-form inverse kinematics (the printed form does
    not converge; the test suite shows it).

    Args:
        p: the structural parameters.
        theta_d: the motor angles, rad.
        phi0: the start attitude (roll, pitch), rad.
        branches: the IK branch per limb (+1 / -1).
        tol: step size at which to stop, rad.
        max_iter: iterations at most.

    Returns:
        The attitude found, the iterations and the final step.

    Raises:
        ClosureNotConverged: no convergence within ``max_iter`` steps, or an iterate leaves the
            workspace (InvKin undefined) or meets a singular B.
    """
    theta_d = np.asarray(theta_d, dtype=float)

    def step(phi: np.ndarray) -> np.ndarray:
        theta = kin.inverse_kinematics(p, phi, branches)
        return kin.jacobian(p, theta, phi) @ ((theta_d - theta + np.pi) % (2 * np.pi) - np.pi)

    return _iterate(step, phi0, tol, max_iter, "paper FK")


def fk_newton(
    p: kin.Geometry, theta_d: Sequence[float], phi0: Sequence[float], tol: float = 1e-13, max_iter: int = 50
) -> FKResult:
    """Newton's method on the constraints (7) at fixed motor angles: ``phi -= B^-1 f(theta_d, phi)``.

    Unlike the paper's iteration it never evaluates the inverse kinematics, so its iterates may
    leave the workspace.

    Args:
        p: the structural parameters.
        theta_d: the motor angles, rad.
        phi0: the start attitude (roll, pitch), rad.
        tol: step size at which to stop, rad.
        max_iter: iterations at most.

    Returns:
        The attitude found, the iterations and the final step.

    Raises:
        ClosureNotConverged: no convergence within ``max_iter`` steps or a singular B.
    """

    def step(phi: np.ndarray) -> np.ndarray:
        _, b = kin.constraint_jacobians(p, theta_d, phi)
        cond = kin.condition(b)
        if cond > 1e12:
            raise SingularConfiguration(cond, "matrix B of eq. (10)")
        return -np.linalg.solve(b, kin.constraint(p, theta_d, phi))

    return _iterate(step, phi0, tol, max_iter, "Newton FK")


def _iterate(
    step: Callable[[np.ndarray], np.ndarray], phi0: Sequence[float], tol: float, max_iter: int, name: str
) -> FKResult:
    """``phi += step(phi)`` until ``|step| <= tol``; failures of ``step`` end it as non-converged."""
    phi = np.array(phi0, dtype=float)
    size = np.inf
    for k in range(1, max_iter + 1):
        try:
            s = step(phi)
        except (InvalidParameters, SingularConfiguration) as err:
            raise ClosureNotConverged(size, tol, k - 1, f"{name}: {err}") from None
        phi += s
        size = float(np.linalg.norm(s))
        if not np.isfinite(size):
            break
        if size <= tol:
            return FKResult(phi, k, size)
    raise ClosureNotConverged(size, tol, max_iter, name)


METHODS = ("paper", "newton", "closure")
#: A regular pose of the cone scene (t = 0.25 s; cond(B) = 1.2), rad.
REGULAR = cone_attitude(0.25)[0]
#: A pose 0.4 deg from the forward singularity det B = 0 (at pitch 25.4 deg for roll 12 deg); cond(B) ~ 70.
NEAR_SINGULAR = np.radians([12.0, 25.0])


def fk_closure(
    mech: Mechanism, theta_d: Sequence[float], phi0: Sequence[float], tol: float = 1e-13, max_iter: int = 50
) -> FKResult:
    """Forward kinematics by the core's closure solver (Gauss-Newton with line search, 4 rows).

    The start is the tree pose with the Hooke joint at phi0, the motors at theta_d, and each middle
    joint turned so that link i2's distal axis is the closest to v_i(phi0) (`kin.limb_angles`).

    Args:
        mech: the platform.
        theta_d: the motor angles, rad.
        phi0: the start attitude (roll, pitch), rad.
        tol: closure residual to reach.
        max_iter: iterations at most.

    Returns:
        The attitude found, the iterations and the final residual.

    Raises:
        ClosureNotConverged: the closure solver failed.
    """
    q0 = tree_q(mech, np.asarray(phi0, float), np.asarray(theta_d, float))
    solved = mech.solve_closure(q0, mech.actuated, tol=tol, max_iter=max_iter)
    q, iters = solved.q, solved.iterations
    phi = np.array([q[mech.q_index("hooke_roll")], q[mech.q_index("hooke_pitch")]])
    return FKResult(phi, iters, float(np.linalg.norm(mech.closure_residual(q))))


def solve_fk(mech: Mechanism, method: str, theta_d: Sequence[float], phi0: Sequence[float]) -> FKResult:
    """One forward-kinematics solve by ``method`` (one of `METHODS`).

    Args:
        mech: the platform.
        method: "paper", "newton" or "closure".
        theta_d: the motor angles, rad.
        phi0: the start attitude (roll, pitch), rad.

    Returns:
        The attitude found, the iterations and the final residual.

    Raises:
        InvalidParameters: an unknown method.
        ClosureNotConverged: the method failed to converge.
    """
    if method == "paper":
        return fk_paper(mech.params, theta_d, phi0, BRANCHES)
    if method == "newton":
        return fk_newton(mech.params, theta_d, phi0)
    if method == "closure":
        return fk_closure(mech, theta_d, phi0)
    raise InvalidParameters("method", method, f"one of {METHODS}")


@dataclass(frozen=True)
class BasinRow:
    """Outcome of one method over the starts at one distance from the answer.

    Attributes:
        method: a name of `METHODS`.
        radius: distance of the starts from the answer in (roll, pitch), rad.
        found: fraction of starts that converged to the answer (within 1e-10 rad).
        elsewhere: fraction that converged to another assembly.
        failed: fraction that did not converge.
        iterations: mean iterations of the starts that found the answer (nan if none).
    """

    method: str
    radius: float
    found: float
    elsewhere: float
    failed: float
    iterations: float


def basin_study(
    mech: Mechanism,
    phi_star: Sequence[float],
    radii: Sequence[float],
    directions: int = 16,
    methods: Sequence[str] = METHODS,
) -> list[BasinRow]:
    """Convergence of each FK method from starts on circles of growing radius about ``phi_star``.

    The motor angles are the paper's IK of phi_star (branch `BRANCHES`); starts are
    ``phi_star + r (cos a, sin a)`` for ``directions`` equally spaced angles a.

    Args:
        mech: the platform.
        phi_star: the target attitude (roll, pitch), rad.
        radii: the start circles' radii, rad.
        directions: starts per circle.
        methods: the FK methods.

    Returns:
        One row per method and radius: the fractions of starts that found the target, another root, or failed, and
            the mean iterations.
    """
    phi_star = np.asarray(phi_star, dtype=float)
    theta_d = kin.inverse_kinematics(mech.params, phi_star, BRANCHES)
    angles = np.linspace(0.0, 2 * np.pi, directions, endpoint=False)
    rows = []
    for method in methods:
        for r in radii:
            found, elsewhere, iters = 0, 0, []
            for a in angles:
                phi0 = phi_star + r * np.array([np.cos(a), np.sin(a)])
                try:
                    res = solve_fk(mech, method, theta_d, phi0)
                except ClosureNotConverged:
                    continue
                error = np.abs((res.phi - phi_star + np.pi) % (2 * np.pi) - np.pi).max()
                if error < 1e-10:
                    found += 1
                    iters.append(res.iterations)
                else:
                    elsewhere += 1
            n = len(angles)
            rows.append(
                BasinRow(
                    method,
                    float(r),
                    found / n,
                    elsewhere / n,
                    (n - found - elsewhere) / n,
                    float(np.mean(iters)) if iters else float("nan"),
                )
            )
    return rows
