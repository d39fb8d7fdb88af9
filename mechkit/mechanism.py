"""`Mechanism`: one closed-loop mechanism built from its parameters, with its kinematics and dynamics."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit.base import arguments
from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.contract import MechanismSpec
from mechkit.catalog.params import MechanismParams
from mechkit.core import batch, dynamics, forward, inverse, kinematics
from mechkit.core import joints as coordinates
from mechkit.core.closures import ClosureRows, cut_rows
from mechkit.core.structure import Structure, analyse
from mechkit.sources.urdf import build_model, parse_loops

Inputs = Mapping[str, float] | Sequence[float] | np.ndarray


class Mechanism:
    """A closed-loop mechanism: Pinocchio model of its tree, closure rows, actuators.

    Attributes:
        spec: the registry entry.
        params: the parameter values used.
        urdf: the generated URDF text.
        model, data: Pinocchio model of the tree and a data for it.
        closures: the loop declarations read from the URDF, with the rows the structure chose.
        structure: loops, sub-mechanisms and Kutzbach count (`mechkit.core.structure.Structure`).
        rows: the closure rows the scene solves with; `full_rows`: all spatial rows (physical joints).
        actuated: actuated joint names (empty: the mechanism is unactuated).
        independent_rows: rank of the closure Jacobian at the home assembly (its generic rank).
    """

    def __init__(self, spec: MechanismSpec, params: MechanismParams, urdf: str, rows: str | None = None,
                 model: pin.Model | None = None, structure: Structure | None = None):
        """Build the model, analyse its structure (`rows="spatial"` forces full rows) and assemble home.

        `model` and `structure`, when given, must be those of `urdf` (a file reader computed them).
        """
        self.spec, self.params, self.urdf = spec, params, urdf
        self._splits: dict[tuple[str, ...], tuple[np.ndarray, np.ndarray]] = {}
        self.model = build_model(urdf) if model is None else model
        forward.check_body_masses(self.model)
        self.data = self.model.createData()
        self.structure = analyse(self.model, parse_loops(urdf), rows) if structure is None else structure
        self.closures = list(self.structure.closures)
        self.cuts = [cut_rows(self.model, c) for c in self.closures]
        self.rows = ClosureRows(self.model, self.cuts)
        self.full_rows = ClosureRows(self.model, [cut_rows(self.model, c, "spatial") for c in self.closures])
        self.actuated = spec.actuated_joints(params)
        for joint in self.actuated:
            self._joint_id(joint)
        self._id_problem = inverse.InverseDynamicsProblem(
            self.model, self.model.createData(), self.rows, self.full_rows,
            np.array([self.v_index(j) for j in self.actuated], dtype=int), self.actuated)
        self.independent_rows = self.rows.size
        self.home_q = self.assemble(spec.home(params))
        self._forward = forward.ForwardSolver(self.model, self.data, self.rows, self.cuts, self.home_q)
        self.independent_rows = kinematics.mobility(self.rows, self.data, self.home_q).rank

    def __repr__(self) -> str:
        """One line: name, coordinates, degrees of freedom, loops, actuators."""
        return (f"<Mechanism {self.spec.name}: nq={self.model.nq}, dof={self.model.nv - self.independent_rows}, "
                f"loops={len(self.closures)}, actuators={list(self.actuated)}>")

    # ---------------------------------------------------------------- indices
    def _joint_id(self, joint: str) -> int:
        if not isinstance(joint, str) or not self.model.existJointName(joint):
            raise InvalidParameters("joint", joint, f"no such joint in {self.spec.name}; joints: {list(self.model.names[1:])}")
        return self.model.getJointId(joint)

    def q_index(self, joint: str) -> int:
        """Index of a one-coordinate joint in q."""
        return self.model.joints[self._joint_id(joint)].idx_q

    def v_index(self, joint: str) -> int:
        """Index of a one-coordinate joint in v."""
        return self.model.joints[self._joint_id(joint)].idx_v

    def neutral(self) -> np.ndarray:
        """Pinocchio's neutral configuration (nq,) of the tree (every joint at zero; loops open)."""
        return pin.neutral(self.model)

    def require_actuators(self, what: str) -> None:
        """Raise `InvalidParameters` naming `what` when the mechanism declares no actuator."""
        if not self.actuated:
            raise InvalidParameters("actuated", (), f"{self.spec.name} is unactuated (its file declares no "
                                    f"<transmission>, name_mot or MJCF actuator): {what} needs actuators; "
                                    "pass actuated=[...] (command line: --actuated J1,J2)")

    def joint_values(self, q: np.ndarray) -> dict[str, float]:
        """Every one-freedom joint's value at q (rad or m; continuous joints as angles)."""
        return coordinates.values(self.model, q)

    def _inputs(self, inputs: Inputs | None, default_names: Sequence[str], arg: str = "inputs") -> dict[str, float]:
        if inputs is None:
            return {}
        if not isinstance(inputs, Mapping) and not default_names:  # values in actuated order, and none is
            self.require_actuators(f"{arg} given in actuated order")
        return arguments.joint_values(arg, inputs, default_names, list(self.model.names[1:]))

    def _state(self, **values: Any) -> list[np.ndarray]:
        """Check state arrays by name (q: nq, v/a/tau: nv), (n,) or (N, n); see `arguments.state`."""
        sizes = {"q": self.model.nq, "v": self.model.nv, "a": self.model.nv, "tau": self.model.nv}
        return arguments.state(sizes, **values)

    def _input_names(self, inputs: Sequence[str] | None, what: str) -> list[str]:
        """The given input joints (default: the actuated ones, which must exist), checked."""
        if inputs is None and not self.actuated:
            self.require_actuators(what)
        return list(self.actuated) if inputs is None else arguments.joint_names("inputs", inputs, list(self.model.names[1:]))

    def _split(self, names: Sequence[str]) -> tuple[np.ndarray, np.ndarray]:
        """Velocity indices of the given joints and of the others, cached per set of names (read-only)."""
        if (key := tuple(names)) not in self._splits:
            input_v = np.array([self.v_index(j) for j in key], dtype=int)
            free_v = np.setdiff1d(np.arange(self.model.nv), input_v)
            input_v.flags.writeable = free_v.flags.writeable = False
            self._splits[key] = input_v, free_v
        return self._splits[key]

    # ---------------------------------------------------------------- kinematics
    def assemble(self, inputs: Inputs, guess: Inputs | np.ndarray | None = None, *, tol: float = kinematics.CLOSURE_TOL,
                 method: str = "newton", max_iter: int = 60) -> np.ndarray:
        """Configuration q that closes every loop with the given input coordinates.

        Args:
            inputs: joint name -> value (rad or m), or values in `actuated` order.
            guess: full q, or joint name -> value, picking the assembly branch (default: the
                spec's guess, else the neutral configuration).
            tol: closure residual to reach (m for position rows).
            method: "newton" (minimum-norm Gauss-Newton) or "lm" (Levenberg-Marquardt).

        Raises:
            ClosureNotConverged: no assembly found near the guess.
        """
        tol = arguments.number("tol", tol, positive=True)
        arguments.option("method", method, kinematics.ASSEMBLY_METHODS)
        max_iter = arguments.integer("max_iter", max_iter, minimum=1)
        given = self._inputs(inputs, self.actuated)
        if guess is None and self.spec.guess is not None:
            guess = self.spec.guess(self.params)
        if guess is None or isinstance(guess, Mapping):
            q0 = self.neutral()
            for joint, value in self._inputs(guess, (), "guess").items():
                coordinates.set_value(self.model, q0, self._joint_id(joint), value)
        else:
            q0 = arguments.array("guess", guess, self.model.nq, batch=False)
        for joint, value in given.items():
            coordinates.set_value(self.model, q0, self._joint_id(joint), value)
        _, free_v = self._split(list(given))
        q, _ = kinematics.solve_closure(self.rows, self.data, q0, free_v, tol=tol, max_iter=max_iter, method=method)
        return q

    def closure_residual(self, q: np.ndarray) -> np.ndarray:
        """Residual of every kept row at q (m for position rows, dimensionless for alignment rows)."""
        q, = self._state(q=q)
        kinematics.update_kinematics(self.model, self.data, q)
        return self.rows.residual(self.data)

    def closure_jacobian(self, q: np.ndarray) -> np.ndarray:
        """(rows, nv) Jacobian of the kept rows at q."""
        q, = self._state(q=q)
        kinematics.update_kinematics(self.model, self.data, q)
        return self.rows.jacobian(self.data)

    def closure_drift(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """gamma(q, v) with d2e/dt2 = J a + gamma."""
        q, v = self._state(q=q, v=v)
        pin.forwardKinematics(self.model, self.data, q, v, np.zeros(self.model.nv))
        pin.updateFramePlacements(self.model, self.data)
        return self.rows.drift(self.data)

    def _kinematic_inputs(self, q: np.ndarray, values: Inputs, names: Sequence[str],
                          arg: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """q as (N, nq), the given values as (N, k), and the input and free velocity indices."""
        if batch.is_batch(q):
            q = batch.sample_array(q, "q", len(q), self.model.nq)
            keys, given = batch.sample_inputs(values, names, len(q))
            arguments.joint_names("inputs", keys, list(self.model.names[1:]), allow_empty=True)
            given = arguments.array(arg, given, len(keys))
        else:
            one = self._inputs(values, names, arg)
            keys, q, given = list(one), q[None], np.array([list(one.values())], dtype=float).reshape(1, -1)
        return (q, given, *self._split(keys))

    def velocities(self, q: np.ndarray, input_rates: Inputs, inputs: Sequence[str] | None = None, *,
                   allow_singular: bool = False) -> kinematics.Conditioned:
        """Joint velocities v from the input rates (rad/s or m/s), J v = 0; `v.condition`: the passive block's.

        Batched: q of shape (N, nq) and rates of shape (N, k) (or joint name -> (N,) values) give (N, nv),
        computed together (`kinematics.velocities`); `condition` is then the largest over the samples.
        Raises `SingularConfiguration` where the inputs do not determine the motion to what the closure
        resolves (`kinematics.resolvable_singular_value`), unless `allow_singular`.
        """
        allow_singular = arguments.flag("allow_singular", allow_singular)
        q, = self._state(q=q)
        names = self._input_names(inputs, "velocities from input rates")
        qs, rates, input_v, free_v = self._kinematic_inputs(q, input_rates, names, "input_rates")
        x, cond = kinematics.velocities(self.rows, self.data, qs, rates, input_v, free_v, self.independent_rows,
                                        allow_singular)
        return kinematics.conditioned(x if batch.is_batch(q) else x[0], cond)

    def accelerations(self, q: np.ndarray, v: np.ndarray, input_accelerations: Inputs,
                      inputs: Sequence[str] | None = None, *, allow_singular: bool = False) -> kinematics.Conditioned:
        """Joint accelerations a from the input accelerations, J a + gamma = 0 (batched like `velocities`;
        `allow_singular` and `a.condition` as in `velocities`)."""
        allow_singular = arguments.flag("allow_singular", allow_singular)
        q, v = self._state(q=q, v=v)
        names = self._input_names(inputs, "accelerations from input accelerations")
        qs, acc, input_v, free_v = self._kinematic_inputs(q, input_accelerations, names, "input_accelerations")
        if batch.is_batch(q):
            v = batch.sample_array(v, "v", len(q), self.model.nv)
        x, cond = kinematics.accelerations(self.rows, self.data, qs, v.reshape(-1, self.model.nv), acc, input_v, free_v,
                                           self.independent_rows, allow_singular)
        return kinematics.conditioned(x if batch.is_batch(q) else x[0], cond)

    def mobility(self, q: np.ndarray | None = None) -> kinematics.Mobility:
        """Numerical DOF and redundant constraints at q (default: the home assembly)."""
        q, = self._state(q=self.home_q if q is None else q)
        return kinematics.mobility(self.rows, self.data, q)

    def singularity(self, q: np.ndarray, inputs: Sequence[str] | None = None) -> float:
        """Condition number of the passive block of the closure Jacobian (inf: singular)."""
        q, = self._state(q=q)
        _, free_v = self._split(self._input_names(inputs, "the singularity measure"))
        return kinematics.passive_condition(self.closure_jacobian(q), free_v, self.independent_rows)

    # ---------------------------------------------------------------- dynamics
    def pin_constraints(self) -> tuple[Any, Any]:
        """Pinocchio `RigidConstraintModel`s (and datas) equivalent to the closures."""
        return self._forward.constraints()

    def forward_dynamics(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray, method: str = "proximal", *,
                         mu: float = 1e-11, accuracy: float = 1e-12, max_iter: int = 20,
                         baumgarte: tuple[float, float] | None = None) -> dynamics.ForwardDynamicsResult:
        """Constrained forward dynamics (constrained ABA): accelerations under joint efforts tau.

        Args:
            method: "proximal" (`pin.constraintDynamics`, proximal settings mu/accuracy/max_iter) or
                "kkt" (dense KKT on the independent rows).
            baumgarte: (Kp (1/s^2), Kd (1/s)) closure stabilisation, J a + gamma + Kd J v + Kp e = 0.
            mu: proximal regularisation, relative to the model (see `forward.ForwardSolver.settings`).
            accuracy: proximal stopping tolerance, relative to the model.
            max_iter: proximal iteration limit.

        Raises `ClosureNotConverged` for a result violating J a + gamma = 0 (`forward.ACCELERATION_TOL`) on
        the rows its method solved (proximal: Pinocchio's anchors, on and off the manifold; KKT: ours),
        `SingularConfiguration` where the accelerations are not unique.

        Batched: q (N, nq), v and tau (N, nv) give a result whose arrays have that leading axis.

        The two methods agree on the closure manifold (e = 0, J v = 0). Off it they differ: each
        method measures the closure error its own way (Pinocchio: point anchors in frame_a's local
        frame; KKT: the rows of `mechkit.core.closures`), so drift is corrected along different paths.
        """
        arguments.option("method", method, forward.METHODS)
        if not forward.plain_state(q, v, tau, self.model.nq, self.model.nv):
            q, v, tau = self._state(q=q, v=v, tau=tau)
        mu, accuracy, max_iter, baumgarte = arguments.solver_settings(mu, accuracy, max_iter, baumgarte)
        solve = self._forward.solve
        if batch.is_batch(q):  # checked once, then every sample on the solver's cached scales
            out = [solve(qi, vi, ti, method, mu=mu, accuracy=accuracy, max_iter=max_iter, baumgarte=baumgarte)
                   for qi, vi, ti in zip(q, v, tau)]
            return dynamics.ForwardDynamicsResult(np.array([r.a for r in out]), np.array([r.constraint_force for r in out]))
        return solve(q, v, tau, method, mu=mu, accuracy=accuracy, max_iter=max_iter, baumgarte=baumgarte)

    def inverse_dynamics(self, q: np.ndarray, v: np.ndarray, a: np.ndarray,
                         fext: pin.StdVec_Force | list[pin.Force] | np.ndarray | list | None = None, determinacy: bool = True,
                         distribution: str = "min_norm", *, allow_singular: bool = False,
                         ) -> dynamics.InverseDynamicsResult | batch.BatchInverseDynamicsResult:
        """Constrained RNEA: actuator efforts and the reaction of every joint (tree and cut).

        Reactions: the wrench parent side -> child side at the joint origin, world frame; see
        `dynamics.JointReaction` for the determinacy flags and `inverse.inverse_dynamics_batch` for
        `fext` (Pinocchio local-frame forces per joint) and `distribution` (redundant actuation).
        Batched: q (N, nq), v and a (N, nv), fext None, (N, njoints, 6) or N per-sample values give
        a `batch.BatchInverseDynamicsResult` (the same numbers as one sample at a time).
        Efforts undetermined to what the closure resolves: `SingularConfiguration` unless `allow_singular`.
        """
        arguments.option("distribution", distribution, inverse.DISTRIBUTIONS)
        determinacy = arguments.flag("determinacy", determinacy)
        q, v, a = self._state(q=q, v=v, a=a)
        rank = None if arguments.flag("allow_singular", allow_singular) else self.independent_rows
        if batch.is_batch(q):
            n, p = len(q), self._id_problem
            return inverse.inverse_dynamics_batch(p, q, v, a, batch.sample_fext(fext, n, self.model.njoints),
                                                  determinacy, distribution, rank)
        fext = arguments.external_forces("fext", fext, self.model.njoints)
        return inverse.inverse_dynamics(self._id_problem, q, v, a, fext, determinacy, distribution, rank)
