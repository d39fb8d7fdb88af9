"""`Mechanism`: one closed-loop mechanism, a thin layer of one-liners over the core.

It holds a `ClosureModel` (built once) and a data (scratch), converts what a user gives (joint names,
values of any joint type, one sample or, in the `*_batch` methods, a leading sample axis) and calls
one core function per quantity. Joint springs and dampers of the description act as passive forces in
both dynamics.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.base import arguments, joint_arguments
from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.catalog.contract import MechanismSpec
from mechkit.catalog.params import MechanismParams
from mechkit.forces import JointSprings

Inputs = Mapping[str, float | Sequence[float]] | Sequence[float] | np.ndarray


class Mechanism:
    """A closed-loop mechanism: a Pinocchio tree (any joints), its closures and couplings, its actuators.

    Args:
        spec: the registry entry (or the one a file reader made).
        params: the parameter values used.
        closure_model: the tree with its closures, couplings and actuation (`mechkit.core.ClosureModel`).
        urdf: the tree's URDF text, where it has one (None: its joints are not URDF's).
        springs: joint springs and dampers (passive forces in the dynamics, `mechkit.forces.JointSprings`).

    Attributes:
        model, data: the Pinocchio model of the tree and a data for it (scratch).
        closures, structure, actuated: as the closure model's. home_q: the home assembly.
        home_mobility: the mobility at home; independent_rows: its rank (the closure's generic rank).
        idle: body -> idle freedoms at home (`mechkit.core.idle_freedoms`: a rod spinning about its axis).

    Raises:
        ClosureNotConverged, SingularConfiguration: the home assembly cannot be found.
    """

    def __init__(self, spec: MechanismSpec, params: MechanismParams, closure_model: core.ClosureModel,
                 urdf: str | None = None, springs: Sequence[core.JointSpring] = ()):
        self.spec, self.params, self.urdf = spec, params, urdf
        self.closure_model = cm = closure_model
        self.closure_data = core_data = cm.create_data()
        self.model, self.data = cm.model, core_data.pin
        self._nq, self._nv = cm.model.nq, cm.model.nv
        self.structure, self.closures, self.actuated = cm.structure, list(cm.closures), cm.actuated
        self.springs = JointSprings(self.model, springs)
        self.home_q = self.assemble(spec.home(params))
        self.home_mobility = core.mobility(cm, core_data, self.home_q)
        self.independent_rows = self.home_mobility.rank
        self.idle = core.idle_freedoms(self.model, self.home_q, core.closure_jacobian(cm, core_data, self.home_q),
                                       set(cm.on_loops), cm.rigid_groups)

    def __repr__(self) -> str:
        """One line: name, coordinates, degrees of freedom, loops, actuators."""
        return (f"<Mechanism {self.spec.name}: nq={self.model.nq}, dof={self.home_mobility.dof}, "
                f"loops={len(self.closures)}, actuators={list(self.actuated)}>")

    @property
    def cuts(self) -> tuple:
        """The closures' kept rows (`CutRows`: closure, frame ids, directions), in closure order."""
        return self.closure_model.kernel.cuts

    # ---------------------------------------------------------------- indices and values
    def joint_id(self, joint: str) -> int:
        """Pinocchio id of a joint (raises `InvalidParameters` naming the joints)."""
        return self.closure_model.joint_id(joint)

    def q_index(self, joint: str) -> int:
        """Index of a joint's first coordinate in q."""
        return self.model.joints[self.joint_id(joint)].idx_q

    def v_index(self, joint: str) -> int:
        """Index of a joint's first velocity coordinate in v."""
        return self.model.joints[self.joint_id(joint)].idx_v

    def neutral(self) -> np.ndarray:
        """Pinocchio's neutral configuration (nq,) of the tree (every joint at zero; loops open)."""
        return pin.neutral(self.model)

    def joint_values(self, q: np.ndarray) -> dict[str, float | np.ndarray]:
        """Every joint's value at q (rad or m; a ball joint's rotation vector, see `mechkit.core.joints`)."""
        return core.joint_values(self.model, q)

    def require_actuators(self, what: str) -> None:
        """Raise `InvalidParameters` naming `what` when the mechanism declares no actuator."""
        if not self.actuated:
            raise InvalidParameters("actuated", (), f"{self.spec.name} is unactuated (its file declares no "
                                    f"<transmission>, name_mot or MJCF actuator): {what} needs actuators; "
                                    "pass actuated=[...] (command line: --actuated J1,J2)")

    def _values(self, values: Inputs | None, names: Sequence[str], arg: str) -> dict[str, Any]:
        """Joint values by name (a mapping, or values in the order of `names`), checked."""
        if values is None:
            return {}
        if not isinstance(values, Mapping) and not names:
            self.require_actuators(f"{arg} given in actuated order")
        sizes = {n: core.joint_size(self.model, self.joint_id(n)) for n in names if self.model.existJointName(n)}
        return joint_arguments.joint_values(arg, values, names, list(self.model.names[1:]), sizes)

    def _names(self, inputs: Sequence[str] | None, what: str) -> list[str]:
        """The given input joints (default: the actuated ones, which must exist), checked."""
        if inputs is None:
            self.require_actuators(what)
            return list(self.actuated)
        return joint_arguments.joint_names("inputs", inputs, list(self.model.names[1:]))

    def _given(self, values: Inputs, names: Sequence[str], arg: str) -> tuple[core.InputSplit, np.ndarray]:
        """The split of the given joints and their values (k,) in velocity order."""
        given = self._values(values, names, arg)
        split = self.closure_model.split(tuple(given))
        return split, np.concatenate([np.atleast_1d(np.asarray(x, dtype=float)) for x in given.values()] or [np.zeros(0)])

    def _given_batch(self, values: Inputs, names: Sequence[str], n: int, arg: str) -> tuple[core.InputSplit, np.ndarray]:
        """The split of the given joints and their values (n, k): a mapping joint -> (n,) or an (n, k) array."""
        sizes = {j: core.joint_size(self.model, self.joint_id(j)) for j in self.model.names[1:]}
        keys, given = joint_arguments.sample_inputs(arg, values, names, n, list(self.model.names[1:]), sizes)
        return self.closure_model.split(tuple(keys)), given

    # ---------------------------------------------------------------- kinematics
    def assemble(self, inputs: Inputs, guess: Inputs | np.ndarray | None = None, *, tol: float = core.CLOSURE_TOL,
                 method: str = "newton", max_iter: int = 60) -> np.ndarray:
        """Configuration q (nq,) that closes every loop with the given joints at the given values.

        Args:
            inputs: joint name -> value (rad or m; a ball joint's rotation vector), or values in
                `actuated` order.
            guess: full q, or joint name -> value, picking the assembly branch (default: the spec's
                guess, else the neutral configuration).
            tol: closure residual to reach (m for position rows).
            method: "newton" (minimum-norm Gauss-Newton) or "lm" (Levenberg-Marquardt).
            max_iter: iteration cap.

        Raises:
            ClosureNotConverged: no assembly found near the guess.
        """
        tol = arguments.number("tol", tol, positive=True)
        arguments.option("method", method, core.ASSEMBLY_METHODS)
        max_iter = arguments.integer("max_iter", max_iter, minimum=1)
        given = self._values(inputs, self.actuated, "inputs")
        if guess is None and self.spec.guess is not None:
            guess = self.spec.guess(self.params)
        if guess is None or isinstance(guess, Mapping):
            q0 = self.neutral()
            for joint, value in self._values(guess, (), "guess").items():
                core.set_joint_value(self.model, q0, self.joint_id(joint), value)
        else:
            q0 = arguments.array("guess", guess, self.model.nq, batch=False)
        for joint, value in given.items():
            core.set_joint_value(self.model, q0, self.joint_id(joint), value)
        split = self.closure_model.split(tuple(given))
        return core.assemble(self.closure_model, self.closure_data, q0, split, tol=tol, max_iter=max_iter, method=method).q

    def solve_closure(self, q0: np.ndarray, fixed: Sequence[str], *, tol: float = core.CLOSURE_TOL, max_iter: int = 60,
                      method: str = "newton") -> core.Assembly:
        """Close every loop from q0 (nq,), keeping the `fixed` joints at q0's values: the solved q, the
        iterations taken and the residual reached (`core.Assembly`); `assemble` with a full start.

        Raises:
            ClosureNotConverged: no assembly found near q0.
        """
        q0, = self._one(q=q0)
        arguments.option("method", method, core.ASSEMBLY_METHODS)
        split = self.closure_model.split(tuple(joint_arguments.joint_names("fixed", fixed, list(self.model.names[1:]),
                                                                     allow_empty=True)))
        return core.assemble(self.closure_model, self.closure_data, q0, split,
                             tol=arguments.number("tol", tol, positive=True),
                             max_iter=arguments.integer("max_iter", max_iter, minimum=1), method=method)

    def _one(self, **values: Any) -> list[np.ndarray]:
        """State arrays of one sample checked by name (q: nq; v, a, tau: nv)."""
        return arguments.sample(self._sizes, **values)

    def _many(self, **values: Any) -> list[np.ndarray]:
        """State arrays of N samples checked by name ((N, nq), (N, nv)), one N for all."""
        return arguments.samples(self._sizes, **values)

    @property
    def _sizes(self) -> dict[str, int]:
        return {"q": self._nq, "v": self._nv, "a": self._nv, "tau": self._nv}

    def closure_residual(self, q: np.ndarray) -> np.ndarray:
        """Residual of every kept row at q (m for position rows, dimensionless for alignment rows)."""
        return core.closure_residual(self.closure_model, self.closure_data, *self._one(q=q))

    def closure_jacobian(self, q: np.ndarray) -> np.ndarray:
        """(rows, nv) Jacobian of the kept rows at q."""
        return core.closure_jacobian(self.closure_model, self.closure_data, *self._one(q=q))

    def closure_drift(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """gamma(q, v) (rows,) with d2e/dt2 = J a + gamma."""
        return core.closure_drift(self.closure_model, self.closure_data, *self._one(q=q, v=v))

    def velocities(self, q: np.ndarray, input_rates: Inputs, inputs: Sequence[str] | None = None, *,
                   allow_singular: bool = False) -> np.ndarray:
        """Joint velocities v (nv,) at q (nq,) from the input rates (rad/s or m/s), J v = 0.

        Raises `SingularConfiguration` where the inputs do not determine the motion to what the closure
        resolves, unless `allow_singular` (then `singularity(q)` tells how far to trust it).
        """
        allow_singular = arguments.flag("allow_singular", allow_singular)
        q, = self._one(q=q)
        split, rates = self._given(input_rates, self._names(inputs, "velocities from input rates"), "input_rates")
        return core.velocities(self.closure_model, self.closure_data, q, split, rates, allow_singular=allow_singular)

    def velocities_batch(self, q: np.ndarray, input_rates: Inputs, inputs: Sequence[str] | None = None, *,
                         allow_singular: bool = False) -> np.ndarray:
        """`velocities` of N samples: q (N, nq), rates (N, k) or joint -> (N,) give (N, nv)."""
        allow_singular = arguments.flag("allow_singular", allow_singular)
        q, = self._many(q=q)
        split, rates = self._given_batch(input_rates, self._names(inputs, "velocities from input rates"), len(q),
                                         "input_rates")
        return core.velocities_batch(self.closure_model, self.closure_data, q, split, rates, allow_singular=allow_singular)

    def accelerations(self, q: np.ndarray, v: np.ndarray, input_accelerations: Inputs, inputs: Sequence[str] | None = None,
                      *, allow_singular: bool = False, least_squares: bool = False) -> np.ndarray:
        """Joint accelerations a (nv,) from the input accelerations, J a + gamma = 0.

        Raises `InconsistentMotion` where gamma leaves the range of J (v is not a motion of the mechanism
        at second order), unless `least_squares` (then the least-squares a, minimum |J a + gamma|).
        """
        allow_singular = arguments.flag("allow_singular", allow_singular)
        least_squares = arguments.flag("least_squares", least_squares)
        q, v = self._one(q=q, v=v)
        names = self._names(inputs, "accelerations from input accelerations")
        split, acc = self._given(input_accelerations, names, "input_accelerations")
        return core.accelerations(self.closure_model, self.closure_data, q, v, split, acc, allow_singular=allow_singular,
                                  least_squares=least_squares)

    def accelerations_batch(self, q: np.ndarray, v: np.ndarray, input_accelerations: Inputs,
                            inputs: Sequence[str] | None = None, *, allow_singular: bool = False,
                            least_squares: bool = False) -> np.ndarray:
        """`accelerations` of N samples: q (N, nq), v (N, nv), input accelerations (N, k) give (N, nv)."""
        allow_singular = arguments.flag("allow_singular", allow_singular)
        least_squares = arguments.flag("least_squares", least_squares)
        q, v = self._many(q=q, v=v)
        names = self._names(inputs, "accelerations from input accelerations")
        split, acc = self._given_batch(input_accelerations, names, len(q), "input_accelerations")
        return core.accelerations_batch(self.closure_model, self.closure_data, q, v, split, acc,
                                        allow_singular=allow_singular, least_squares=least_squares)

    def mobility(self, q: np.ndarray | None = None) -> core.Mobility:
        """Numerical DOF and redundant constraints at q (default: the home assembly)."""
        if q is None:
            return self.home_mobility
        return core.mobility(self.closure_model, self.closure_data, *self._one(q=q))

    def singularity(self, q: np.ndarray, inputs: Sequence[str] | None = None) -> float:
        """Condition number of the passive block of the closure Jacobian (inf: singular)."""
        q, = self._one(q=q)
        split = self.closure_model.split(tuple(self._names(inputs, "the singularity measure")))
        return core.passive_condition(self.closure_model, self.closure_data, q, split)

    def second_order_inconsistency(self, q: np.ndarray, v: np.ndarray) -> float:
        """min over a of max |J a + gamma|: 0 where v is a motion of the mechanism at second order."""
        return core.second_order_inconsistency(self.closure_model, self.closure_data, *self._one(q=q, v=v))

    def second_order_velocity(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The velocity (nv,) near v with J v = 0 along which the motion continues at second order."""
        return core.second_order_velocity(self.closure_model, self.closure_data, *self._one(q=q, v=v))

    # ---------------------------------------------------------------- dynamics
    def generalized_forces(self, efforts: Mapping[str, float] | Sequence[float] | np.ndarray) -> np.ndarray:
        """The generalised forces S^T u (nv,) of actuator efforts u (N m or N): by actuator name, or in
        `actuated` order (a joint motor acts on its joint; a transmission on its joints)."""
        self.require_actuators("generalised forces from efforts")
        u = joint_arguments.joint_values("efforts", efforts, self.actuated, self.actuated) if isinstance(efforts, Mapping) \
            else dict(zip(self.actuated, arguments.array("efforts", efforts, len(self.actuated), batch=False)))
        return self.closure_model.actuation.T @ np.array([u.get(a, 0.0) for a in self.actuated], dtype=float)

    def passive_forces(self, q: np.ndarray, v: np.ndarray) -> np.ndarray | None:
        """Generalised forces (nv,) or (N, nv) of the joint springs and dampers, None without any."""
        return self.springs.forces(q, v) if self.springs else None

    def forward_dynamics(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray, method: str = "proximal", *,
                         mu: float | None = None, accuracy: float | None = None, max_iter: int | None = None,
                         baumgarte: tuple[float, float] | None = None) -> core.ForwardDynamicsResult:
        """Constrained forward dynamics: accelerations (nv,) under joint efforts tau (nv,) (and the springs).

        Args:
            method: "proximal", "lcaba", "kkt" or "nullspace" (`mechkit.core.forward`).
            mu, accuracy, max_iter: Pinocchio's settings for "proximal" and "lcaba", relative to the
                model (None: `core.FORWARD_DEFAULTS`).
            baumgarte: (Kp (1/s^2), Kd (1/s)) closure stabilisation, J a + gamma + Kd J v + Kp e = 0.

        Raises:
            ConstraintViolated: a result violating J a + gamma = 0 on the rows its method solved.
            InconsistentMotion: gamma leaves the range of J (no rigid answer at this state).
            SingularConfiguration: accelerations not unique.
        """
        arguments.option("method", method, core.FORWARD_METHODS)
        proximal = method == "proximal"  # a NaN or inf argument gives it non-finite accelerations: named on failure
        if not arguments.plain_state(q, v, tau, self._nq, self._nv, finite=not proximal):
            q, v, tau = self._one(q=q, v=v, tau=tau)
        settings = {} if mu is None and accuracy is None and max_iter is None and baumgarte is None \
            else arguments.solver_settings(mu, accuracy, max_iter, baumgarte)
        try:
            return core.forward_dynamics(self.closure_model, self.closure_data, q, v,
                                         tau + self.springs.forces(q, v) if self.springs else tau, method, **settings)
        except SingularConfiguration:
            if proximal:
                self._one(q=q, v=v, tau=tau)
            raise

    def forward_dynamics_batch(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray, method: str = "proximal", *,
                               mu: float | None = None, accuracy: float | None = None, max_iter: int | None = None,
                               baumgarte: tuple[float, float] | None = None) -> core.ForwardDynamicsResult:
        """`forward_dynamics` of N states: q (N, nq), v and tau (N, nv) give arrays with that leading axis."""
        arguments.option("method", method, core.FORWARD_METHODS)
        q, v, tau = self._many(q=q, v=v, tau=tau)
        settings = arguments.solver_settings(mu, accuracy, max_iter, baumgarte)
        passive = self.passive_forces(q, v)
        return core.forward_dynamics_batch(self.closure_model, self.closure_data, q, v,
                                           tau if passive is None else tau + passive, method, **settings)

    def inverse_dynamics(self, q: np.ndarray, v: np.ndarray, a: np.ndarray, fext: Any = None, determinacy: bool = True,
                         distribution: str = "min_norm", *, allow_singular: bool = False) -> core.InverseDynamicsResult:
        """Constrained RNEA of one sample: actuator efforts and the reaction of every joint (tree and cut).

        Args:
            q, v, a: (nq,), (nv,), (nv,) a motion satisfying the closures (J a + gamma = 0).
            fext: None, one `pin.Force` per joint or an (njoints, 6) array (local frames, universe first).
            determinacy: flag the reaction components statics does not fix.
            distribution: "min_norm" or "min_effort" where redundant actuation leaves a family.
            allow_singular: skip the test that the inputs determine the motion.

        Raises:
            SingularConfiguration: the efforts are undetermined to what the closure resolves.
        """
        arguments.option("distribution", distribution, core.DISTRIBUTIONS)
        determinacy = arguments.flag("determinacy", determinacy)
        if not arguments.plain_state(q, v, a, self._nq, self._nv):
            q, v, a = self._one(q=q, v=v, a=a)
        if fext is not None:
            fext = joint_arguments.external_forces("fext", fext, self.model.njoints)
        return core.inverse_dynamics(self.closure_model, self.closure_data, q, v, a, fext, self.passive_forces(q, v),
                                     determinacy_test=determinacy, distribution=distribution,
                                     generic_rank=None if arguments.flag("allow_singular", allow_singular)
                                     else self.independent_rows, idle=bool(self.idle))

    def inverse_dynamics_batch(self, q: np.ndarray, v: np.ndarray, a: np.ndarray, fext: Any = None,
                               determinacy: bool = True, distribution: str = "min_norm", *,
                               allow_singular: bool = False) -> core.BatchInverseDynamicsResult:
        """`inverse_dynamics` of N samples: q (N, nq), v and a (N, nv); fext None, (N, njoints, 6) or N
        per-sample values. Efforts (N, na), reactions (N, joints, 6): the same numbers as one at a time."""
        arguments.option("distribution", distribution, core.DISTRIBUTIONS)
        determinacy = arguments.flag("determinacy", determinacy)
        q, v, a = self._many(q=q, v=v, a=a)
        fexts = joint_arguments.sample_fext("fext", fext, len(q), self.model.njoints)
        return core.inverse_dynamics_batch(self.closure_model, self.closure_data, q, v, a, fexts,
                                           self.passive_forces(q, v), determinacy_test=determinacy,
                                           distribution=distribution,
                                           generic_rank=None if arguments.flag("allow_singular", allow_singular)
                                     else self.independent_rows, idle=bool(self.idle))

    # ---------------------------------------------------------------- in time
    def simulate(self, duration: float, **options: Any) -> Any:
        """The mechanism moving for `duration` seconds under its forces, drives and events: a
        `mechkit.simulation.SimulationResult` (options: `mechkit.simulation.simulate`)."""
        from mechkit.simulation import simulate
        return simulate(self, duration, **options)

    def equilibrium(self, held: Mapping[str, float] | None = None, **options: Any) -> Any:
        """The static equilibrium where gravity, the springs and the `held` inputs (joint -> value) balance:
        a `mechkit.simulation.Equilibrium` (options: `mechkit.simulation.equilibrium`)."""
        from mechkit.simulation import equilibrium
        return equilibrium(self, held, **options)
