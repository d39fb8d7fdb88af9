"""`Mechanism`: one closed-loop mechanism, a thin layer of one-liners over the core.

It holds a `ClosureModel` (built once) and a data (scratch), converts what a user gives (joint names,
values of any joint type, one sample or, in the `*_batch` methods, a leading sample axis) and calls
one core function per quantity. Joint springs and dampers of the description act as passive forces in
both dynamics.

Its methods come in three layers: the joints by name and the closure (assembly, closure rows,
mobility, singularity: `mechkit.mechanism_closure.MechanismClosure`), the velocities and
accelerations from the inputs (`mechkit.mechanism_rates.MechanismRates`), and here its construction,
its dynamics (forward and inverse, one sample or N) and its motion in time.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mechkit import core
from mechkit.base import arguments, joint_arguments
from mechkit.base.exceptions import SingularConfiguration
from mechkit.catalog.contract import MechanismSpec
from mechkit.catalog.params import MechanismParams
from mechkit.forces import JointSprings
from mechkit.mechanism_rates import MechanismRates


class Mechanism(MechanismRates):
    """A closed-loop mechanism: a Pinocchio tree (any joints), its closures and couplings, its actuators.

    Its joints by name, assembly and closure rows: `MechanismClosure`; its velocities and accelerations
    from the inputs: `MechanismRates` (both inherited).

    Args:
        spec: the registry entry (or the one a file reader made).
        params: the parameter values used.
        closure_model: the tree with its closures, couplings and actuation (`mechkit.core.ClosureModel`).
        urdf: the tree's URDF text, where it has one (None: its joints are not URDF's).
        springs: joint springs and dampers (passive forces in the dynamics, `mechkit.forces.JointSprings`).
        source_urdf: the URDF it was reduced from (`mechkit.reduction`), when `urdf` is None: its elements
            that name links and joints (beams, elastic joints) still apply to the mechanism.

    Attributes:
        model, data: the Pinocchio model of the tree and a data for it (scratch).
        closures, structure, actuated: as the closure model's. home_q: the home assembly;
        home_assembly: its record (the branch it took, the joints it leaves outside their limits).
        home_mobility: the mobility at home; independent_rows: its rank (the closure's generic rank).
        idle: body -> idle freedoms at home (`mechkit.core.idle_freedoms`: a rod spinning about its axis).

    Raises:
        ClosureNotConverged, SingularConfiguration: the home assembly cannot be found.
    """

    def __init__(
        self,
        spec: MechanismSpec,
        params: MechanismParams,
        closure_model: core.ClosureModel,
        urdf: str | None = None,
        springs: Sequence[core.JointSpring] = (),
        source_urdf: str | None = None,
    ):
        self.spec, self.params, self.urdf, self.source_urdf = spec, params, urdf, source_urdf
        self.closure_model = cm = closure_model
        self.closure_data = core_data = cm.create_data()
        self.model, self.data = cm.model, core_data.pin
        self._nq, self._nv = cm.model.nq, cm.model.nv
        self.structure, self.closures, self.actuated = cm.structure, list(cm.closures), cm.actuated
        self.springs = JointSprings(self.model, springs, cuts=cm.kernel.cuts)
        self.home_assembly = self.assembly(spec.home(params))
        self.home_q = self.home_assembly.q
        self.home_mobility = core.mobility(cm, core_data, self.home_q)
        self.independent_rows = self.home_mobility.rank
        self.idle = core.idle_freedoms(
            self.model,
            self.home_q,
            core.closure_jacobian(cm, core_data, self.home_q),
            set(cm.on_loops),
            cm.rigid_groups,
        )

    def __repr__(self) -> str:
        """One line: name, coordinates, degrees of freedom, loops, actuators."""
        return (
            f"<Mechanism {self.spec.name}: nq={self.model.nq}, dof={self.home_mobility.dof}, "
            f"loops={len(self.closures)}, actuators={list(self.actuated)}>"
        )

    @property
    def cuts(self) -> tuple:
        """The closures' kept rows (`CutRows`: closure, frame ids, directions), in closure order."""
        return self.closure_model.kernel.cuts

    # ---------------------------------------------------------------- dynamics
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
        self.require_actuators("generalised forces from efforts")
        u = (
            joint_arguments.joint_values("efforts", efforts, self.actuated, self.actuated)
            if isinstance(efforts, Mapping)
            else dict(zip(self.actuated, arguments.array("efforts", efforts, len(self.actuated), batch=False)))
        )
        return self.closure_model.actuation.T @ np.array([u.get(a, 0.0) for a in self.actuated], dtype=float)

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
        arguments.option("method", method, core.FORWARD_METHODS)
        proximal = method == "proximal"  # a NaN or inf argument gives it non-finite accelerations: named on failure
        if not arguments.plain_state(q, v, tau, self._nq, self._nv, finite=not proximal):
            q, v, tau = self._one(q=q, v=v, tau=tau)
        settings = (
            {}
            if mu is None and accuracy is None and max_iter is None and baumgarte is None
            else arguments.solver_settings(mu, accuracy, max_iter, baumgarte)
        )
        try:
            return core.forward_dynamics(
                self.closure_model,
                self.closure_data,
                q,
                v,
                tau + self.springs.forces(q, v) if self.springs else tau,
                method,
                **settings,
            )
        except SingularConfiguration:
            if proximal:
                self._one(q=q, v=v, tau=tau)
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
        q, v, tau = self._many(q=q, v=v, tau=tau)
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
            q, v, a = self._one(q=q, v=v, a=a)
        if fext is not None:
            fext = joint_arguments.external_forces("fext", fext, self.model.njoints)
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
            generic_rank=None if arguments.flag("allow_singular", allow_singular) else self.independent_rows,
            idle=bool(self.idle),
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
        q, v, a = self._many(q=q, v=v, a=a)
        fexts = joint_arguments.sample_fext("fext", fext, len(q), self.model.njoints)
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
            generic_rank=None if arguments.flag("allow_singular", allow_singular) else self.independent_rows,
            idle=bool(self.idle),
        )

    # ---------------------------------------------------------------- in time
    def simulate(self, duration: float, **options: Any) -> Any:
        """The mechanism moving under its forces, drives and events.

        Args:
            duration: simulated time (s).
            **options: those of `mechkit.simulation.simulate` (inputs, torques, forces, dt, ...).

        Returns:
            The motion, energies and closure residual (`mechkit.simulation.SimulationResult`).
        """
        from mechkit.simulation import simulate

        return simulate(self, duration, **options)

    def equilibrium(self, held: Mapping[str, float] | None = None, **options: Any) -> Any:
        """The static equilibrium where gravity, the springs and the held inputs balance.

        Args:
            held: joint name -> value (rad or m) of the inputs held still (default: none).
            **options: those of `mechkit.simulation.equilibrium` (elements, q0, tol, max_iter).

        Returns:
            The pose, its residual and its stability (`mechkit.simulation.Equilibrium`).
        """
        from mechkit.simulation import equilibrium

        return equilibrium(self, held, **options)
