"""`MechanismDynamics`: a mechanism's constrained dynamics, forward and inverse, one sample or N.

The generalised forces of actuator efforts and of the joint springs and dampers, the accelerations
under given efforts (forward) and the efforts and every joint's reaction under a given motion (inverse,
with the test that the inputs determine the motion and the flags of what statics leaves undetermined);
one core function per quantity, over the closure model and a data it shares with the mechanism's other
parts, with joints and state arrays checked by name through a `JointNaming`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mechkit import core
from mechkit.base import arguments, joint_arguments
from mechkit.base.exceptions import SingularConfiguration
from mechkit.forces import JointSprings
from mechkit.mechanism_naming import JointNaming

#: What `MechanismDynamics.forward_dynamics` passes to Pinocchio unconverted: float64 arrays.
_ARRAY, _FLOAT = np.ndarray, np.dtype(np.float64)


class MechanismDynamics:
    """Forward and inverse dynamics of a closed-loop mechanism under its springs and dampers.

    Args:
        naming: the mechanism's joints by name (`JointNaming`).
        closure_model: the tree with its closures, couplings and actuation (`mechkit.core.ClosureModel`).
        closure_data: a data of it (scratch).
        springs: the joint springs and dampers (passive forces in both dynamics).
        generic_rank: the closure's generic rank (`MechanismClosure.independent_rows`): fewer independent
            rows at a state is a singular configuration.
        idle: whether some body has idle freedoms (`MechanismClosure.idle`), which the determinacy test
            leaves aside.
    """

    def __init__(
        self,
        naming: JointNaming,
        closure_model: core.ClosureModel,
        closure_data: Any,
        springs: JointSprings,
        generic_rank: int,
        idle: bool,
    ):
        self.naming, self.closure_model, self.closure_data = naming, closure_model, closure_data
        self.springs, self.generic_rank, self.idle = springs, generic_rank, idle
        self._nq, self._nv, self._njoints = closure_model.model.nq, closure_model.model.nv, closure_model.model.njoints

    def generalized_forces(self, efforts: Mapping[str, float] | Sequence[float] | np.ndarray) -> np.ndarray:
        """The generalised forces of actuator efforts (a joint motor acts on its joint; a tendon on its
        joints).

        Args:
            efforts: actuator name -> effort u (N m or N; one not named: 0), or efforts in `actuated` order.

        Returns:
            (nv,) S^T u.

        Raises:
            InvalidParameters: the mechanism is unactuated.
        """
        self.naming.require_actuators("generalised forces from efforts")
        u = (
            joint_arguments.joint_values("efforts", efforts, self.naming.actuated, self.naming.actuated)
            if isinstance(efforts, Mapping)
            else dict(
                zip(self.naming.actuated, arguments.array("efforts", efforts, len(self.naming.actuated), batch=False))
            )
        )
        return self.closure_model.actuation.T @ np.array([u.get(a, 0.0) for a in self.naming.actuated], dtype=float)

    def passive_forces(self, q: np.ndarray, v: np.ndarray) -> np.ndarray | None:
        """Generalised forces of the joint springs and dampers.

        Args:
            q: (nq,) or (N, nq) configurations.
            v: (nv,) or (N, nv) joint velocities.

        Returns:
            (nv,) or (N, nv) the forces (N m or N), None when the mechanism has no spring.
        """
        return self.springs.forces(q, v) if self.springs else None

    def forward_dynamics(
        self,
        q: np.ndarray,
        v: np.ndarray,
        tau: np.ndarray,
        method: str = "proximal",
        *,
        mu: float | None = None,
        accuracy: float | None = None,
        max_iter: int | None = None,
        baumgarte: tuple[float, float] | None = None,
    ) -> core.ForwardDynamicsResult:
        """Constrained forward dynamics: the accelerations under joint efforts (and the springs).

        Args:
            q: (nq,) the configuration.
            v: (nv,) the joint velocities.
            tau: (nv,) the generalised joint efforts (N m or N; `generalized_forces` of actuator efforts).
            method: "proximal", "lcaba", "kkt" or "nullspace" (`mechkit.core.forward`).
            mu: Pinocchio's proximal regularisation for "proximal" and "lcaba", relative to the model
                (None: `core.FORWARD_DEFAULTS`).
            accuracy: their stopping tolerance (m/s^2 for position rows; None: the default).
            max_iter: their iteration cap (None: the default).
            baumgarte: (Kp (1/s^2), Kd (1/s)) closure stabilisation, J a + gamma + Kd J v + Kp e = 0.

        Returns:
            The accelerations a (nv,), the generalised constraint force J^T lambda (nv,) and the solver's
            iterations (`core.ForwardDynamicsResult`).

        Raises:
            ConstraintViolated: a result violating J a + gamma = 0 on the rows its method solved.
            InconsistentMotion: gamma leaves the range of J (no rigid answer at this state).
            SingularConfiguration: accelerations not unique.
        """
        default = type(method) is str and method == "proximal"
        if not default:
            arguments.option("method", method, core.FORWARD_METHODS)
        # "proximal" reads its arguments in Pinocchio alone, which refuses wrong sizes (ValueError) and gives
        # non-finite accelerations for a NaN or inf: float64 vectors go straight to it, named on failure
        proximal = default and not self.springs.springs
        if not (
            (
                type(q) is _ARRAY
                and type(v) is _ARRAY
                and type(tau) is _ARRAY
                and q.dtype is _FLOAT
                and v.dtype is _FLOAT
                and tau.dtype is _FLOAT
                and q.ndim == v.ndim == tau.ndim == 1
            )
            if proximal
            else arguments.plain_state(q, v, tau, self._nq, self._nv, finite=method != "proximal")
        ):
            q, v, tau = self.naming.one(q=q, v=v, tau=tau)
        if self.springs.springs:
            tau = tau + self.springs.forces(q, v)
        try:
            if mu is None and accuracy is None and max_iter is None and baumgarte is None:
                return core.forward_dynamics(self.closure_model, self.closure_data, q, v, tau, method)
            settings = arguments.solver_settings(mu, accuracy, max_iter, baumgarte)
            return core.forward_dynamics(self.closure_model, self.closure_data, q, v, tau, method, **settings)
        except (SingularConfiguration, ValueError):
            if method == "proximal":
                self.naming.one(q=q, v=v, tau=tau)
            raise

    def forward_dynamics_batch(
        self,
        q: np.ndarray,
        v: np.ndarray,
        tau: np.ndarray,
        method: str = "proximal",
        *,
        mu: float | None = None,
        accuracy: float | None = None,
        max_iter: int | None = None,
        baumgarte: tuple[float, float] | None = None,
    ) -> core.ForwardDynamicsResult:
        """`forward_dynamics` of N states at once.

        Args:
            q: (N, nq) configurations.
            v: (N, nv) joint velocities.
            tau: (N, nv) generalised joint efforts (N m or N).
            method: as `forward_dynamics`.
            mu: as `forward_dynamics`.
            accuracy: as `forward_dynamics`.
            max_iter: as `forward_dynamics`.
            baumgarte: as `forward_dynamics`.

        Returns:
            The result with arrays of leading axis N (a and J^T lambda (N, nv)).
        """
        arguments.option("method", method, core.FORWARD_METHODS)
        q, v, tau = self.naming.many(q=q, v=v, tau=tau)
        settings = arguments.solver_settings(mu, accuracy, max_iter, baumgarte)
        passive = self.passive_forces(q, v)
        return core.forward_dynamics_batch(
            self.closure_model, self.closure_data, q, v, tau if passive is None else tau + passive, method, **settings
        )

    def inverse_dynamics(
        self,
        q: np.ndarray,
        v: np.ndarray,
        a: np.ndarray,
        fext: Any = None,
        determinacy: bool = True,
        distribution: str = "min_norm",
        *,
        allow_singular: bool = False,
    ) -> core.InverseDynamicsResult:
        """Constrained RNEA of one sample: actuator efforts and the reaction of every joint (tree and cut).

        Args:
            q: (nq,) an assembled configuration.
            v: (nv,) joint velocities with J v = 0.
            a: (nv,) joint accelerations with J a + gamma = 0.
            fext: None, one `pin.Force` per joint or an (njoints, 6) array (local frames, universe first).
            determinacy: flag the reaction components statics does not fix.
            distribution: "min_norm" or "min_effort" where redundant actuation leaves a family.
            allow_singular: skip the test that the inputs determine the motion.

        Returns:
            The efforts (N m or N) by actuator, the reactions [f, m] (N, N m; world axes, moment about the
            joint origin) of every tree and cut joint, the closure multipliers and the determinacy flags
            (`core.InverseDynamicsResult`).

        Raises:
            SingularConfiguration: the efforts are undetermined to what the closure resolves.
        """
        arguments.option("distribution", distribution, core.DISTRIBUTIONS)
        determinacy = arguments.flag("determinacy", determinacy)
        if not arguments.plain_state(q, v, a, self._nq, self._nv):
            q, v, a = self.naming.one(q=q, v=v, a=a)
        if fext is not None:
            fext = joint_arguments.external_forces("fext", fext, self._njoints)
        return core.inverse_dynamics(
            self.closure_model,
            self.closure_data,
            q,
            v,
            a,
            fext,
            self.passive_forces(q, v),
            determinacy_test=determinacy,
            distribution=distribution,
            generic_rank=None if arguments.flag("allow_singular", allow_singular) else self.generic_rank,
            idle=self.idle,
        )

    def inverse_dynamics_batch(
        self,
        q: np.ndarray,
        v: np.ndarray,
        a: np.ndarray,
        fext: Any = None,
        determinacy: bool = True,
        distribution: str = "min_norm",
        *,
        allow_singular: bool = False,
    ) -> core.BatchInverseDynamicsResult:
        """`inverse_dynamics` of N samples at once (the same numbers as one at a time).

        Args:
            q: (N, nq) assembled configurations.
            v: (N, nv) joint velocities.
            a: (N, nv) joint accelerations.
            fext: None, (N, njoints, 6) wrenches in each joint's local frame (universe first), or N
                values as `inverse_dynamics` takes.
            determinacy: as `inverse_dynamics`.
            distribution: as `inverse_dynamics`.
            allow_singular: as `inverse_dynamics`.

        Returns:
            Efforts (N, na) and reactions (N, joints, 6) (`core.BatchInverseDynamicsResult`).
        """
        arguments.option("distribution", distribution, core.DISTRIBUTIONS)
        determinacy = arguments.flag("determinacy", determinacy)
        q, v, a = self.naming.many(q=q, v=v, a=a)
        fexts = joint_arguments.sample_fext("fext", fext, len(q), self._njoints)
        return core.inverse_dynamics_batch(
            self.closure_model,
            self.closure_data,
            q,
            v,
            a,
            fexts,
            self.passive_forces(q, v),
            determinacy_test=determinacy,
            distribution=distribution,
            generic_rank=None if arguments.flag("allow_singular", allow_singular) else self.generic_rank,
            idle=self.idle,
        )
