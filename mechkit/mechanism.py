"""`Mechanism`: one closed-loop mechanism built from its parameters, with its kinematics and dynamics."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit import batch, dynamics, inverse, kinematics
from mechkit.closures import ClosureRows, cut_rows, rigid_constraint_models
from mechkit.description import build_model, parse_loops, render_urdf
from mechkit.exceptions import InvalidParameters, MethodUnavailable, SingularConfiguration
from mechkit.params import MechanismParams
from mechkit.contract import MechanismSpec
from mechkit.registry import get_spec

Inputs = Mapping[str, float] | Sequence[float] | np.ndarray


class Mechanism:
    """A closed-loop mechanism: Pinocchio model of its tree, closure rows, actuators.

    Attributes:
        spec: the registry entry.
        params: the parameter values used.
        urdf: the generated URDF text.
        model, data: Pinocchio model of the tree and a data for it.
        closures: the loop declarations read from the URDF.
        rows: the closure rows the scene solves with; `full_rows`: all spatial rows (physical joints).
        actuated: actuated joint names.
        independent_rows: rank of the closure Jacobian at the home assembly (its generic rank).
    """

    def __init__(self, spec: MechanismSpec, params: MechanismParams, urdf: str):
        self.spec, self.params, self.urdf = spec, params, urdf
        self.model = build_model(urdf)
        self.data = self.model.createData()
        self.closures = parse_loops(urdf)
        self.cuts = [cut_rows(self.model, c) for c in self.closures]
        self.rows = ClosureRows(self.model, self.cuts)
        self.full_rows = ClosureRows(self.model, [cut_rows(self.model, c, "spatial") for c in self.closures])
        self.actuated = spec.actuated_joints(params)
        for joint in self.actuated:
            self._joint_id(joint)
        self._id_problem = inverse.InverseDynamicsProblem(
            self.model, self.model.createData(), self.rows, self.full_rows,
            np.array([self.v_index(j) for j in self.actuated], dtype=int), self.actuated)
        self._pin_constraints: tuple | None = None
        self._pin_baumgarte = (0.0, 0.0)
        self._kkt_rows: np.ndarray | None = None
        self.independent_rows = self.rows.size
        self.home_q = self.assemble(spec.home(params))
        self.independent_rows = kinematics.mobility(self.rows, self.data, self.home_q).rank

    # ---------------------------------------------------------------- indices
    def _joint_id(self, joint: str) -> int:
        if not self.model.existJointName(joint):
            raise InvalidParameters("joint", joint, f"no such joint in {self.spec.name}; joints: {list(self.model.names[1:])}")
        return self.model.getJointId(joint)

    def q_index(self, joint: str) -> int:
        """Index of a one-coordinate joint in q."""
        return self.model.joints[self._joint_id(joint)].idx_q

    def v_index(self, joint: str) -> int:
        """Index of a one-coordinate joint in v."""
        return self.model.joints[self._joint_id(joint)].idx_v

    def neutral(self) -> np.ndarray:
        return pin.neutral(self.model)

    def _inputs(self, inputs: Inputs | None, default_names: Sequence[str]) -> dict[str, float]:
        if inputs is None:
            return {}
        if isinstance(inputs, Mapping):
            return {k: float(v) for k, v in inputs.items()}
        values = np.atleast_1d(np.asarray(inputs, dtype=float))
        if values.size != len(default_names):
            raise InvalidParameters("inputs", list(values), f"expected {len(default_names)} values for {list(default_names)}")
        return dict(zip(default_names, values))

    def _split(self, names: Sequence[str]) -> tuple[np.ndarray, np.ndarray]:
        input_v = np.array([self.v_index(j) for j in names], dtype=int)
        free_v = np.setdiff1d(np.arange(self.model.nv), input_v)
        return input_v, free_v

    # ---------------------------------------------------------------- kinematics
    def assemble(self, inputs: Inputs, guess: Inputs | np.ndarray | None = None, *, tol: float = 1e-12,
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
        given = self._inputs(inputs, self.actuated)
        if guess is None and self.spec.guess is not None:
            guess = self.spec.guess(self.params)
        if isinstance(guess, np.ndarray) and guess.shape == (self.model.nq,):
            q0 = guess.astype(float).copy()
        else:
            q0 = self.neutral()
            for joint, value in self._inputs(guess, ()).items():
                q0[self.q_index(joint)] = value
        for joint, value in given.items():
            if not np.isfinite(value):
                raise InvalidParameters(joint, value, "input must be finite")
            q0[self.q_index(joint)] = value
        _, free_v = self._split(list(given))
        q, _ = kinematics.solve_closure(self.rows, self.data, q0, free_v, tol=tol, max_iter=max_iter, method=method)
        return q

    def closure_residual(self, q: np.ndarray) -> np.ndarray:
        """Residual of every kept row at q (m for position rows, dimensionless for alignment rows)."""
        kinematics.update_kinematics(self.model, self.data, q)
        return self.rows.residual(self.data)

    def closure_jacobian(self, q: np.ndarray) -> np.ndarray:
        """(rows, nv) Jacobian of the kept rows at q."""
        kinematics.update_kinematics(self.model, self.data, q)
        return self.rows.jacobian(self.data)

    def closure_drift(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """gamma(q, v) with d2e/dt2 = J a + gamma."""
        pin.forwardKinematics(self.model, self.data, q, v, np.zeros(self.model.nv))
        pin.updateFramePlacements(self.model, self.data)
        return self.rows.drift(self.data)

    def velocities(self, q: np.ndarray, input_rates: Inputs, inputs: Sequence[str] | None = None) -> np.ndarray:
        """Joint velocities v from the input rates (rad/s or m/s), J v = 0.

        Batched: q of shape (N, nq) and rates of shape (N, k) (or joint name -> (N,) values) give (N, nv).

        Raises:
            SingularConfiguration: the inputs do not determine the motion at q.
        """
        if batch.is_batch(q):
            q = batch.sample_array(q, "q", len(q), self.model.nq)
            keys, rates = batch.sample_inputs(input_rates, list(inputs or self.actuated), len(q))
            return np.array([self.velocities(qi, ri, keys) for qi, ri in zip(q, rates)]).reshape(len(q), self.model.nv)
        names = list(inputs or self.actuated)
        rates = self._inputs(input_rates, names)
        input_v, free_v = self._split(list(rates))
        J = self.closure_jacobian(q)
        return kinematics.project_velocity(J, np.array(list(rates.values())), input_v, free_v, self.independent_rows)

    def accelerations(self, q: np.ndarray, v: np.ndarray, input_accelerations: Inputs,
                      inputs: Sequence[str] | None = None) -> np.ndarray:
        """Joint accelerations a from the input accelerations, J a + gamma = 0 (batched like `velocities`)."""
        if batch.is_batch(q):
            q = batch.sample_array(q, "q", len(q), self.model.nq)
            keys, acc = batch.sample_inputs(input_accelerations, list(inputs or self.actuated), len(q))
            v = batch.sample_array(v, "v", len(q), self.model.nv)
            return np.array([self.accelerations(qi, vi, ai, keys) for qi, vi, ai in zip(q, v, acc)]).reshape(
                len(q), self.model.nv)
        names = list(inputs or self.actuated)
        acc = self._inputs(input_accelerations, names)
        input_v, free_v = self._split(list(acc))
        J = self.closure_jacobian(q)
        gamma = self.closure_drift(q, v)
        return kinematics.project_velocity(J, np.array(list(acc.values())), input_v, free_v, self.independent_rows, rhs=gamma)

    def mobility(self, q: np.ndarray | None = None) -> kinematics.Mobility:
        """Numerical DOF and redundant constraints at q (default: the home assembly)."""
        return kinematics.mobility(self.rows, self.data, self.home_q if q is None else q)

    def singularity(self, q: np.ndarray, inputs: Sequence[str] | None = None) -> float:
        """Condition number of the passive block of the closure Jacobian (inf: singular)."""
        _, free_v = self._split(list(inputs or self.actuated))
        return kinematics.passive_condition(self.closure_jacobian(q), free_v, self.independent_rows)

    # ---------------------------------------------------------------- dynamics
    def pin_constraints(self) -> tuple[Any, Any]:
        """Pinocchio `RigidConstraintModel`s (and datas) equivalent to the closures."""
        if self._pin_constraints is None:
            cms = pin.StdVec_RigidConstraintModel()
            for cm in rigid_constraint_models(self.model, self.cuts):
                cms.append(cm)
            cds = pin.StdVec_RigidConstraintData()
            for cm in cms:
                cds.append(cm.createData())
            self._pin_data = self.model.createData()
            pin.initConstraintDynamics(self.model, self._pin_data, cms, cds)
            self._pin_constraints = (cms, cds)
        return self._pin_constraints

    def forward_dynamics(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray, method: str = "proximal", *,
                         mu: float = 1e-9, accuracy: float = 1e-12, max_iter: int = 20,
                         baumgarte: tuple[float, float] | None = None) -> dynamics.ForwardDynamicsResult:
        """Constrained forward dynamics (constrained ABA): accelerations under joint efforts tau.

        Args:
            method: "proximal" (`pin.constraintDynamics`, proximal settings mu/accuracy/max_iter) or
                "kkt" (dense KKT on the independent rows).
            baumgarte: (Kp (1/s^2), Kd (1/s)) closure stabilisation, J a + gamma + Kd J v + Kp e = 0.

        Batched: q (N, nq), v and tau (N, nv) give a result whose arrays have that leading axis.

        The two methods agree on the closure manifold (e = 0, J v = 0). Off it they differ: each
        method measures the closure error its own way (Pinocchio: point anchors in frame_a's local
        frame; KKT: the rows of `mechkit.closures`), so drift is corrected along different paths.
        """
        if batch.is_batch(q):
            n = len(q)
            q = batch.sample_array(q, "q", n, self.model.nq)
            v, tau = batch.sample_array(v, "v", n, self.model.nv), batch.sample_array(tau, "tau", n, self.model.nv)
            out = [self.forward_dynamics(qi, vi, ti, method, mu=mu, accuracy=accuracy, max_iter=max_iter,
                                         baumgarte=baumgarte) for qi, vi, ti in zip(q, v, tau)]
            return dynamics.ForwardDynamicsResult(np.array([r.a for r in out]).reshape(n, -1),
                                                  np.array([r.constraint_force for r in out]).reshape(n, -1))
        tau = np.asarray(tau, dtype=float)
        if method == "proximal":
            cms, cds = self.pin_constraints()
            gains = (0.0, 0.0) if baumgarte is None else tuple(baumgarte)
            if gains != self._pin_baumgarte:
                for cm in cms:
                    cm.setBaumgarteCorrectorParameters(pin.BaumgarteCorrectorParameters(*gains))
                self._pin_baumgarte = gains
            prox = pin.ProximalSettings(accuracy, mu, max_iter)
            data = self._pin_data
            a = pin.constraintDynamics(self.model, data, q, v, tau, cms, cds, prox).copy()
            if not np.all(np.isfinite(a)):
                raise SingularConfiguration(float("inf"), f"pin.constraintDynamics returned non-finite accelerations (mu={mu})")
            result = dynamics.ForwardDynamicsResult(a, pin.rnea(self.model, data, q, v, a) - tau)
        elif method == "kkt":
            J = self.closure_jacobian(q)
            gamma = self.closure_drift(q, v)
            if baumgarte is not None:
                kp, kd = baumgarte
                gamma = gamma + kd * (J @ v) + kp * self.rows.residual(self.data)
            if self._kkt_rows is None:
                self._kkt_rows = dynamics.independent_rows(self.closure_jacobian(self.home_q))
            try:
                result = dynamics.kkt_forward(self.model, self.data, q, v, tau, J, gamma, self._kkt_rows)
            except SingularConfiguration:  # the cached rows lost rank here: choose rows at this q
                result = dynamics.kkt_forward(self.model, self.data, q, v, tau, J, gamma)
        else:
            raise MethodUnavailable(method, "forward_dynamics methods are 'proximal' and 'kkt'")
        return result

    def inverse_dynamics(self, q: np.ndarray, v: np.ndarray, a: np.ndarray, fext=None, determinacy: bool = True,
                         distribution: str = "min_norm") -> dynamics.InverseDynamicsResult | batch.BatchInverseDynamicsResult:
        """Constrained RNEA: actuator efforts and the reaction of every joint (tree and cut).

        Reactions: the wrench parent side -> child side at the joint origin, world frame; see
        `dynamics.JointReaction` for the determinacy flags and `inverse.inverse_dynamics_batch` for
        `fext` (Pinocchio local-frame forces per joint) and `distribution` (redundant actuation).
        Batched: q (N, nq), v and a (N, nv), fext None, (N, njoints, 6) or N per-sample values give
        a `batch.BatchInverseDynamicsResult` (the same numbers as one sample at a time).
        """
        if batch.is_batch(q):
            n, p = len(q), self._id_problem
            q = batch.sample_array(q, "q", n, self.model.nq)
            v, a = batch.sample_array(v, "v", n, self.model.nv), batch.sample_array(a, "a", n, self.model.nv)
            return inverse.inverse_dynamics_batch(p, q, v, a, batch.sample_fext(fext, n, self.model.njoints),
                                                  determinacy, distribution)
        return inverse.inverse_dynamics(self._id_problem, q, v, a, fext, determinacy, distribution)


def load(name: str, **params: Any) -> Mechanism:
    """Build a registered mechanism from its parameters (unknown names raise `InvalidParameters`)."""
    spec = get_spec(name)
    values = spec.params.from_overrides(**params)
    return from_params(spec, values)


def from_params(spec: MechanismSpec, params: MechanismParams) -> Mechanism:
    """Build a mechanism from a parameter instance."""
    return Mechanism(spec, params, render_urdf(spec.template_path, params.xacro_args()))


def from_urdf(urdf: str, actuated: Sequence[str] | None = None, name: str = "urdf",
              guess: Mapping[str, float] | None = None) -> Mechanism:
    """Wrap any URDF text (a tree, or with `<mechkit:loop>` closures) as a Mechanism.

    Args:
        urdf: URDF text.
        actuated: actuated joint names (default: every joint of the tree).
        name: a name for reports.
        guess: joint name -> value near which the loops are closed for the home configuration
            (default: the neutral configuration).
    """
    model = build_model(urdf)
    joints = tuple(actuated) if actuated is not None else tuple(model.names[1:])
    spec = MechanismSpec(name=name, params=MechanismParams, template="", actuated=joints,
                         gruebler_dof=model.nv, home=lambda p: {}, guess=(lambda p: guess) if guess else None,
                         summary=f"loaded from URDF ({name})")
    return Mechanism(spec, MechanismParams(), urdf)
