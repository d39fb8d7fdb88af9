"""Singular positions and redundant constraints in a simulation: where the closure rows lose rank, the
motion is followed on its own branch, and a branch change is reported by name, never passed off as an
answer.

The scheme (ours, after the projection methods of constrained dynamics: e.g. Bayo and Avello,
"Singularity-free augmented Lagrangian algorithms for constrained multibody dynamics", Nonlinear
Dynamics 5 (1994) 209-231, whose two-four-bar example the IFToMM benchmark "N four-bar mechanism"
extends):

- The rank of the closure Jacobian J is decided by its SVD relative to its largest singular value
  (`mechkit.core.RANK_TOL`): dependent rows are dropped in every solve (the projections:
  `mechkit.simulation.projection`; the accelerations: the core's SVD null-space method).
- `ratio(q)`, the smallest singular value of the mechanism's generic rank over the largest, measures
  the distance to a singular position (0 there: the four-bar chain lying flat). Where it is below
  `NEAR` or the mechanism has redundant rows, the integrator's stages are evaluated at their projection
  onto the manifold (`on_manifold`): off it, near a singular position or with redundant rows, the drift
  gamma leaves the range of J by the stage's own error, which the ill-conditioned rows amplify; on it
  the accelerations are those of the branch, and the step size no longer collapses.
- After each step the projection must not change the state beyond the step's own error: a projected
  position away from the integrated one by more than `JUMP` of the step, or, near a singular position
  (ratio below `NEAR` at the step's end, or a step that may reach one), a velocity whose kinetic energy
  the projection changes by more than `BRANCH_TOL` of it, means the state landed on another branch (its
  tangent no longer holds the velocity it arrived with). The step is taken again smaller; where that
  does not help, `BranchChanged` names the time and the joint. Away from singular positions the tangent
  is unique: the velocity projection's change there is the step's own error (the energy balance's).
- A singular position passed on the branch is an event of the result (`Crossing`): its time (the
  smallest ratio seen), the joint moving most along the freedom that opens there, the mobility there.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin
import scipy.linalg
import scipy.optimize

from mechkit import core
from mechkit.base.exceptions import (
    ConstraintViolated,
    InconsistentMotion,
    MechkitError,
    SingularConfiguration,
)
from mechkit.simulation.integrator import IntegrationFailed

Vec = np.ndarray
#: Ratio below which a state counts as near a singular position (ours: the stages are projected there).
NEAR = 1e-2
#: Largest relative change of the kinetic energy by the velocity projection near a singular position (ours:
#: the integrator's error is far below it; a velocity across another branch's tangent far above).
BRANCH_TOL = 1e-4
#: Largest position change by the projection, relative to the step's own displacement (ours).
JUMP = 0.1
#: Singular values below this fraction of the largest count as lost at a crossing (ours).
LOST = 1e-2
#: A crossing's ratio is below this fraction of the ratio at both ends of its step (ours).
DIP = 0.1
#: Rank threshold of the accelerations on the manifold, relative to the largest singular value (ours: gamma is in
#: J's range there, so it only drops a redundant row, left near 1e-12 by a projection to `POSITION_TOL` (kept, the
#: 9RR-12URU's steps collapsed at 1e-13); a stage within 1e-10 of a singular position: error control sees it).
TIGHT = 1e-10


class BranchChanged(MechkitError):
    """The motion left its branch at a singular position (or the steps could not stay on it).

    Attributes:
        t: the time (s).
        joint: the joint that moved most off the branch.
        change: the relative change the projection would have made (kinetic energy or position).
    """

    def __init__(self, t: float, joint: str, change: float, what: str):
        self.t, self.joint, self.change = t, joint, change
        super().__init__(
            f"the motion left its branch at t = {t:.6g} s, joint {joint!r}: {what} (relative {change:.3g})"
        )


@dataclass(frozen=True)
class Crossing:
    """A singular position passed on the branch.

    Attributes:
        t: the time of the smallest ratio seen (s).
        joint: the joint moving most along the freedom that opens there.
        ratio: the smallest ratio seen.
        mobility: the mobility there (singular values below `LOST` of the largest counted as lost).
    """

    t: float
    joint: str
    ratio: float
    mobility: int


class BranchWatch:
    """The rank of one mechanism's closure rows along a simulation.

    Args:
        mech (Mechanism): the mechanism.
        q: (nq,) an assembled configuration where its rank is the generic one.
    """

    def __init__(self, mech, q: np.ndarray):
        self.mech = mech
        self.cm = mech.closure_model
        self.cd = self.cm.create_data()
        self.names = [self.mech.model.names[j] for j in range(1, self.mech.model.njoints)]
        J = core.closure_jacobian(self.cm, self.cd, q)
        s = np.linalg.svd(J, compute_uv=False) if J.size else np.zeros(0)
        self.rank = core.numerical_rank(s) if s.size else 0
        self.redundant = J.shape[0] - self.rank
        self.crossings: list[Crossing] = []
        self._last: tuple[float, float] | None = None
        self.start = 1.0
        self.start = self.ratio(q)[0]

    def ratio(self, q: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
        """The distance to a singular position.

        Args:
            q: (nq,) configuration.

        Returns:
            (sigma_rank / sigma_1 relative to its value at the start (1 without rows), the singular values
            over sigma_1, the right singular vector of sigma_rank (nv,)).
        """
        J = core.closure_jacobian(self.cm, self.cd, q)
        if not self.rank:
            return 1.0, np.zeros(0), np.zeros(self.cm.nv)
        _, s, Vt = np.linalg.svd(J)
        return float(s[self.rank - 1] / s[0]) / self.start, s / s[0], Vt[self.rank - 1]

    def joint_of(self, dv: np.ndarray) -> str:
        """The joint with the largest component of a velocity-space vector.

        Args:
            dv: (nv,) the vector.

        Returns:
            The joint's name.
        """
        k = int(np.argmax(np.abs(dv)))
        return self.names[_joint_of_v(self.mech.model, k) - 1]

    def check(self, t: float, q0: Vec, q_step: Vec, v_step: Vec, q: Vec, v: Vec, searching: bool = True) -> None:
        """Refuse a projection that moved the state off the branch it arrived on.

        Args:
            t: the step's end (s).
            q0: (nq,) the configuration at the step's start.
            q_step: (nq,) the integrated configuration at its end.
            v_step: (nv,) the integrated velocity there.
            q: (nq,) the projected configuration.
            v: (nv,) the projected velocity.
            searching: the step may have reached a singular position (`approaching`); otherwise the
                kinetic-energy test applies only where the end's ratio is below `NEAR`.

        Raises:
            BranchChanged: a position jump above `JUMP` of the step, or (near a singular position) a
                kinetic-energy change above `BRANCH_TOL`.
        """
        moved = float(np.linalg.norm(q_step - q0))
        jump = float(np.linalg.norm(q - q_step))
        if jump > JUMP * moved and jump > 1e-9:
            raise BranchChanged(
                t, self.joint_of(q - q_step), jump / max(moved, 1e-300), "the closure moved the position"
            )
        kinetic, dv = float(pin.computeKineticEnergy(self.cm.model, self.cd.pin, q, v_step)), v - v_step  # no M
        change = float(pin.computeKineticEnergy(self.cm.model, self.cd.pin, q, dv)) / kinetic if kinetic > 0 else 0.0
        if change > BRANCH_TOL and (searching or self.ratio(q)[0] < NEAR):
            raise BranchChanged(t, self.joint_of(dv), change, "the velocity left the tangent of the branch")

    def approaching(self, t: float, q: np.ndarray, h: float | None, s: np.ndarray | None = None) -> bool:
        """Whether the next step may reach a singular position: a ratio below `NEAR` at q, or one the last
        two steps' trend brings below it within the next step (a step can straddle a singular position
        between two states far from it).

        Args:
            t: the time (s).
            q: (nq,) the configuration at the step's start.
            h: the next step's size (s), or None.
            s: the closure Jacobian's singular values at q where known (`Projection.singular_values`).

        Returns:
            True near a singular position.
        """
        if s is None and self.rank:  # the values only: `ratio`'s first
            s = np.linalg.svd(core.closure_jacobian(self.cm, self.cd, q), compute_uv=False)
        r = float(s[self.rank - 1] / s[0]) / self.start if self.rank else 1.0
        last, self._last = self._last, (t, r)
        if r < NEAR:
            return True
        if last is None or h is None or t <= last[0]:
            return False
        slope = (r - last[1]) / (t - last[0])
        return r + 1.5 * slope * h < NEAR

    def passed(
        self, dense: Callable[[float], np.ndarray], t0: float, t1: float, q_of: Callable[[np.ndarray], np.ndarray]
    ) -> Crossing | None:
        """The singular position a near-singular step passed, if any: the smallest ratio on the step's
        dense output (bounded Brent search), counted where it falls below `LOST` and below `DIP` times the
        ratio at both ends (a minimum inside the step, not the approach of the next one).

        Args:
            dense: the step's dense output, t -> y.
            t0: the step's start (s).
            t1: its end (s).
            q_of: y -> (nq,) configuration.

        Returns:
            The `Crossing`, or None.
        """
        if t1 <= t0:
            return None
        found = scipy.optimize.minimize_scalar(
            lambda t: self.ratio(q_of(dense(t)))[0], bounds=(t0, t1), method="bounded", options={"xatol": 1e-9}
        )
        tc = float(found.x)
        r, s, w = self.ratio(q_of(dense(tc)))
        ends = min(self.ratio(q_of(dense(t0)))[0], self.ratio(q_of(dense(t1)))[0])
        if not (r < LOST and r < DIP * ends):
            return None
        crossing = Crossing(tc, self.joint_of(w), r, self.cm.nv - int(np.sum(s > LOST * self.start)))
        self.crossings.append(crossing)
        return crossing


def _joint_of_v(model, k: int) -> int:
    """The joint (index) whose velocity coordinates hold index k."""
    for j in range(1, model.njoints):
        if model.joints[j].idx_v <= k < model.joints[j].idx_v + model.joints[j].nv:
            return j
    return 0


#: Smallest ratio sigma_rank / sigma_1 at the start for which the near-singular mode is taken before the
#: method asked fails (ours). Projecting the stages amplifies the projection's rounding by the inverse of
#: the rows' smallest singular value: measured on the deployable 9RR-12URU (ratio 1.7e-5), a 1e-12 change
#: of a stage's position moved its projected accelerations by 2e-3 of 41 rad/s^2 and the steps collapsed
#: at rtol 1e-11; the benchmarks' ratios are 0.35 (N four-bar) and 0.62 (Bricard).
CONDITIONED = 1e-3
#: Failures of a step in the method asked that send it to the near-singular mode.
FALLBACK = (InconsistentMotion, ConstraintViolated, SingularConfiguration, IntegrationFailed)


class BranchMode:
    """Which equations a simulation's steps integrate: the method asked, or the stages projected onto the
    manifold with their null-space accelerations (`forward`, the system's method "branch").

    The near-singular mode is taken where a step may reach a singular position (`BranchWatch.approaching`)
    or the rows are redundant, on mechanisms whose rows are conditioned (`CONDITIONED`); elsewhere a step
    runs in the method asked, and where it fails (`FALLBACK`: the core's checks refuse the accelerations
    at the stages off the manifold, or the step size collapses) or lands off its branch
    (`BranchChanged`), it is taken again in the near-singular mode: for the rest of the run where it
    failed away from a singular position, else until the step's start is away from one again.

    Args:
        watch: the mechanism's `BranchWatch`, or None (no projection: the method asked only).
        system (MechanismSystem): the equations (its `method` is switched).
        dynamics: the method asked.
        stepper (Stepper): the integrator (restarted where the mode changes).
    """

    def __init__(self, watch: BranchWatch | None, system: Any, dynamics: str, stepper: Any):
        self.watch, self.system, self.dynamics, self.stepper = watch, system, dynamics, stepper
        self.near = self.fallen = self.stay = self.searching = False

    def _set(self, near: bool, t: float, y: np.ndarray) -> None:
        """Switch the mode (an ill-conditioned mechanism's is the core's exact "nullspace" method, its
        stages not projected) and restart the stepper at (t, y)."""
        conditioned = self.watch is not None and self.watch.start >= CONDITIONED
        self.fallen = near
        self.near = near and conditioned
        self.system.method = ("branch" if conditioned else "nullspace") if near else self.dynamics
        self.stepper.restart(t, y)

    def before(self, t: float, q: np.ndarray, y: np.ndarray, s: np.ndarray | None = None) -> None:
        """At a step's start: whether it may reach a singular position (`searching`: its crossing is then
        looked for), and back to the method asked where the ratio has recovered.

        Args:
            t: the time (s).
            q: (nq,) the configuration.
            y: the integrated vector.
            s: the closure Jacobian's singular values at q where known.
        """
        if self.watch is None:
            return
        self.searching = self.watch.approaching(t, q, self.stepper.h, s)
        proactive = self.watch.start >= CONDITIONED and (self.searching or self.watch.redundant > 0)
        near = self.stay or proactive
        if near != self.fallen:
            self._set(near, t, y)

    def fallback(self, err: Exception, t: float, q: np.ndarray, y: np.ndarray) -> None:
        """A step failed in the method asked: take it again in the near-singular mode.

        Args:
            err: the failure.
            t: the step's start (s).
            q: (nq,) the configuration there.
            y: the integrated vector there.

        Raises:
            IntegrationFailed: the step size collapsed in the near-singular mode too (with the joint along
                the closure rows' weakest direction), or there is no watch.
            Exception: `err` itself where it is not a step size's collapse and the mode cannot help.
        """
        if self.watch is None or self.fallen:
            if isinstance(err, IntegrationFailed):
                joint = self.watch.joint_of(self.watch.ratio(q)[2]) if self.watch is not None else ""
                raise IntegrationFailed(t, err.why, joint) from None
            raise err
        self.stay = self.watch.ratio(q)[0] >= NEAR or self.watch.start < CONDITIONED
        self._set(True, t, y)

    def retry(self, err: BranchChanged, last: bool, t: float, t1: float, y: np.ndarray) -> None:
        """A step landed off its branch: again in the near-singular mode, then at a quarter of its size.

        Args:
            err: the branch change.
            last: no retry is left.
            t: the step's start (s).
            t1: its end (s).
            y: the integrated vector at its start.

        Raises:
            BranchChanged: `err`, where no retry is left.
        """
        if last:
            raise err
        if self.fallen:
            self.stepper.h = (t1 - t) / 4
            self.stepper.restart(t, y)
        else:
            self._set(True, t, y)


def forward(cm: core.ClosureModel, cd: core.ClosureData, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """Accelerations on the manifold: a = a_p + N z, a_p = -J^+ gamma and N a basis of the null space of
    J from its SVD truncated at `TIGHT`, z from the reduced mass matrix N^T M N (the null-space method
    with the rank resolved down to rounding, for states projected onto the manifold).

    Args:
        cm: the closure model.
        cd: a data of it (scratch).
        q: (nq,) an assembled configuration.
        v: (nv,) a velocity with J v = 0.
        tau: (nv,) joint efforts (N m or N).

    Returns:
        (nv,) the accelerations.

    Raises:
        SingularConfiguration: a free motion carries no inertia (N^T M N not positive definite).
    """
    model = cm.model
    J = core.closure_jacobian(cm, cd, q)
    gamma = core.closure_drift(cm, cd, q, v)
    M = pin.crba(model, cd.pin, q)
    M = np.triu(M) + np.triu(M, 1).T
    rhs = tau - pin.nonLinearEffects(model, cd.pin, q, v)
    if not J.size:
        return np.linalg.solve(M, rhs)
    U, s, Vt = np.linalg.svd(J)
    r = int(np.sum(s > TIGHT * s[0]))
    a_p = -Vt[:r].T @ ((U[:, :r].T @ gamma) / s[:r])
    N = Vt[r:].T
    try:
        L = np.linalg.cholesky(N.T @ M @ N)
    except np.linalg.LinAlgError:
        raise SingularConfiguration(
            float("inf"), "reduced mass matrix N^T M N: a free motion carries no inertia"
        ) from None
    z = scipy.linalg.cho_solve((L, True), N.T @ (rhs - M @ a_p))
    return a_p + N @ z


def on_manifold(projection: Any, drives: Any, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A stage's state projected onto the closures and drives (`Projection`).

    Args:
        projection (Projection): the projection.
        drives: the driven joints.
        t: the stage's time (s).
        q: (nq,) its configuration.
        v: (nv,) its velocity.

    Returns:
        (q, v) on the manifold.
    """
    q = projection.positions(q, drives, t)
    return q, projection.velocities(q, v, drives, t)
