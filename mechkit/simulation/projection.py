"""Projection onto the constraint manifold after each accepted step: closures and driven joints.

Positions: the driven joints are set to their law's values (held joints to theirs) and the other
coordinates are moved by Gauss-Newton steps of minimum norm, dq_F = -J_F^+ e, with J_F^+ the pseudo-inverse
truncated where the singular values fall below `core.RANK_TOL` times the largest (times the rows' own
smallest ratio where the mechanism is ill-conditioned: `rank_floor`): dependent rows (a
redundant constraint, as in Bricard's linkage, or the rows that coincide at a singular position) are
dropped by the SVD instead of feeding rounding into the step. A state whose closure residual is within
`DRIFT_TOL` is left as it is (one kinematic pass, no iteration: the cost of a fixed step's projection); the
residual and the closure Jacobian of the last projected configuration are kept for the velocity projection
and the recorder (`Projection.residual`). The loops close to `POSITION_TOL` in a few
steps from a state one integrator step away; where they do not, the core's global closure solve
(`mechkit.core.assemble`) is tried from there. Velocities: the driven joints' rates are set to the law's,
and the other coordinates get the minimum-norm correction dv_F = -J_F^+ (J v) (same truncation), i.e. the
orthogonal projection onto the null space of the rows J_F has. At a singular position (the null space
grows: the four-bar chain lying flat) the velocity keeps its component along the directions that open
there: the branch's own tangent the motion arrived with, not a least-norm choice among the new
freedoms (`mechkit.simulation.crossing` watches the branch). Both are the smallest changes, in the
coordinates, that put the state back on the manifold; what they change in the energy is part of the
integrator's error, which the energy balance shows.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.simulation.prescribed import Drives

#: Closure residual (m for position rows) the position projection reaches (ours: below the 1e-10 m the
#: simulation promises, above round-off for metre-sized mechanisms).
POSITION_TOL = 1e-12
#: Closure residual (m) up to which a state is left where it is (ours: a tenth of the 1e-10 m promised). A
#: fixed step's drift is far below it (RK4 at MuJoCo's step: 1e-15 m a step), so most steps skip the
#: Gauss-Newton iterations; once the drift has grown past it, the state is closed to rounding again.
DRIFT_TOL = 1e-11
#: Gauss-Newton steps of the local closure before the core's global solve is tried (ours: from one
#: integrator step away the local steps converge quadratically in two or three).
LOCAL_STEPS = 8
#: Gain per step below which the local closure has reached rounding (ours: Newton's steps gain far more).
POLISH = 4.0


def truncated_solve(
    J: np.ndarray, b: np.ndarray, floor: float = core.RANK_TOL, svd: tuple[np.ndarray, ...] | None = None
) -> np.ndarray:
    """The minimum-norm least-squares solution of J x = b, singular values below `floor` times the largest
    dropped (dependent rows, and the directions a singular position adds, left alone).

    Args:
        J: (rows, n) the matrix.
        b: (rows,) the right-hand side.
        floor: the relative threshold.
        svd: J's thin SVD (U, s, Vt) where already known.

    Returns:
        (n,) x.
    """
    if not J.size:
        return np.zeros(J.shape[1])
    U, s, Vt = svd if svd is not None else np.linalg.svd(J, full_matrices=False)
    r = int(np.sum(s > floor * s[0]))
    return Vt[:r].T @ ((U[:, :r].T @ b) / s[:r])


def rank_floor(cm: core.ClosureModel, q: np.ndarray) -> float:
    """The relative threshold of a mechanism's truncated solves: `core.RANK_TOL` times its rows' smallest
    nonzero singular value over the largest at q, where below 1 (ours: an ill-conditioned mechanism's
    own rows, the deployable 9RR-12URU's at 1.7e-5, are not dropped as a singular position's would be).

    Args:
        cm: the closure model.
        q: (nq,) an assembled configuration where its rank is the generic one.

    Returns:
        The threshold, relative to the largest singular value.
    """
    J = core.closure_jacobian(cm, cm.create_data(), q)
    if not J.size:
        return core.RANK_TOL
    s = np.linalg.svd(J, compute_uv=False)
    r = core.numerical_rank(s)
    return core.RANK_TOL * min(1.0, float(s[r - 1] / s[0])) if r else core.RANK_TOL


class Projection:
    """Projects states of one mechanism onto its closures and its drives.

    Args:
        mech (Mechanism): the mechanism (`mechkit.Mechanism`).
        tol: closure residual to reach (m).
        drift_tol: closure residual (m) up to which a configuration is left as it is (0: always projected).
    """

    def __init__(self, mech, tol: float = POSITION_TOL, drift_tol: float = DRIFT_TOL):
        self.mech, self.tol, self.drift_tol = mech, tol, drift_tol
        self._last: tuple[np.ndarray, float, np.ndarray] | None = None
        self._svd: tuple[np.ndarray, tuple[np.ndarray, ...]] | None = None
        self.cm = mech.closure_model
        self.cd = self.cm.create_data()
        self.model = self.cm.model
        self.floor = rank_floor(self.cm, mech.home_q)

    def rows(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The closure residual and Jacobian at a configuration, from one kinematic pass.

        Args:
            q: (nq,) configuration.

        Returns:
            (rows,) residuals (m for position rows) and (rows, nv) the closure Jacobian.
        """
        G, J, _ = core.kinematic_pass(self.cm, self.cd, q[None])
        e, Jc, _ = self.cm.kernel.evaluate(G[0], J[0], q)  # `core.closure_residual`'s rows to rounding (1e-17 m)
        return e, Jc

    def positions(self, q: np.ndarray, drives: Drives, t: float) -> np.ndarray:
        """A configuration with the driven joints on their law and every loop closed (left as it is where its
        residual is within `drift_tol`).

        Args:
            q: (nq,) the configuration to project.
            drives: the driven joints.
            t: the time (s) their law is taken at.

        Returns:
            (nq,) the projected configuration.

        Raises:
            ClosureNotConverged: the loops do not close near q.
        """
        q = np.array(q, dtype=float)
        values, _, _ = drives.at(t)
        for joint, value in zip(drives.all, values):
            core.set_joint_value(self.model, q, self.mech.joint_id(joint), float(value))
        split = self.cm.split(drives.all)
        e, J = self.rows(q)
        r = float(np.max(np.abs(e), initial=0.0))
        if r <= self.drift_tol:
            self._last = (q, r, J)
            return q
        local = self._local(q, split.free_v, e, J)
        if local is not None:
            self._last = local
            return local[0]
        q = core.assemble(self.cm, self.cd, q, split, tol=self.tol, jacobian_at_trials=False).q
        self._last = (q, *self._rows_max(q))
        return q

    def _rows_max(self, q: np.ndarray) -> tuple[float, np.ndarray]:
        """max |residual| and the Jacobian at q."""
        e, J = self.rows(q)
        return float(np.max(np.abs(e), initial=0.0)), J

    def _local(
        self, q: np.ndarray, free: np.ndarray, e: np.ndarray, J: np.ndarray
    ) -> tuple[np.ndarray, float, np.ndarray] | None:
        """Truncated Gauss-Newton from q (residual e, Jacobian J) over the free coordinates, on to rounding once
        `tol` is met (until a step gains less than `POLISH`: a projection that stops anywhere below `tol` leaves
        noise of that size, which the velocity projection amplifies by the inverse of the rows' smallest
        singular value): (q, its residual, its Jacobian), or None where it does not reach `tol`."""
        step = np.zeros(self.model.nv)
        previous, before = np.inf, (q, np.inf, J)
        for _ in range(LOCAL_STEPS):
            r = float(np.max(np.abs(e), initial=0.0))
            if previous <= self.tol and r > previous / POLISH:
                return (q, r, J) if r <= previous else before
            if r == 0.0:
                return q, r, J
            step[:] = 0.0
            step[free] = -truncated_solve(J[:, free], e, self.floor)
            if not np.isfinite(step).all():
                return None
            previous, before = r, (q, r, J)
            q = pin.integrate(self.model, q, step)
            e, J = self.rows(q)
        r = float(np.max(np.abs(e), initial=0.0))
        return (q, r, J) if r <= self.tol else (before if previous <= self.tol else None)

    def _known(self, q: np.ndarray) -> tuple[np.ndarray, float, np.ndarray] | None:
        """The last projected configuration's (q, residual, Jacobian) where q is it, else None."""
        last = self._last
        return last if last is not None and (last[0] is q or np.array_equal(last[0], q)) else None

    def velocities(self, q: np.ndarray, v: np.ndarray, drives: Drives, t: float) -> np.ndarray:
        """Velocities with the driven joints' rates on their law and J v = 0.

        Args:
            q: (nq,) an assembled configuration.
            v: (nv,) the velocities to project.
            drives: the driven joints.
            t: the time (s) their law is taken at.

        Returns:
            (nv,) the projected velocities (the undriven ones changed by the least-norm correction, the
            directions a singular position adds kept).
        """
        v = np.array(v, dtype=float)
        split = self.cm.split(drives.all)
        _, rates, _ = drives.at(t)
        v[split.input_v] = rates
        known = self._known(q)
        J = known[2] if known is not None else self.rows(q)[1]
        if J.shape[0]:
            free = split.free_v
            whole = free.size == J.shape[1]  # no driven joint: the SVD is the whole Jacobian's, kept for q
            svd = self._svd_of(q, J) if whole else None
            v[free] -= truncated_solve(J[:, free], J @ v, self.floor, svd)
        return v

    def _svd_of(self, q: np.ndarray, J: np.ndarray) -> tuple[np.ndarray, ...]:
        """The thin SVD of the closure Jacobian J at q (kept for `singular_values`)."""
        self._svd = (q, np.linalg.svd(J, full_matrices=False))
        return self._svd[1]

    def singular_values(self, q: np.ndarray) -> np.ndarray:
        """The closure Jacobian's singular values at q (those of the last velocity projection's SVD where it was
        made at q).

        Args:
            q: (nq,) configuration.

        Returns:
            (min(rows, nv),) the singular values, largest first.
        """
        if self._svd is not None and (self._svd[0] is q or np.array_equal(self._svd[0], q)):
            return self._svd[1][1]
        known = self._known(q)
        J = known[2] if known is not None else self.rows(q)[1]
        return np.linalg.svd(J, compute_uv=False)

    def residual(self, q: np.ndarray) -> float:
        """The largest closure residual at a configuration.

        Args:
            q: (nq,) configuration.

        Returns:
            max |residual| (m for position rows).
        """
        known = self._known(q)
        return known[1] if known is not None else self._rows_max(q)[0]
