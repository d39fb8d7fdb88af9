"""`Mechanism`: one closed-loop mechanism built from its parameters, with its kinematics and dynamics."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit import arguments, batch, dynamics, kinematics
from mechkit.closures import ClosureRows, cut_rows, rigid_constraint_models
from mechkit.contract import MechanismSpec
from mechkit.description import build_model, parse_loops, render_urdf
from mechkit.exceptions import InvalidArgument, InvalidParameters, SingularConfiguration
from mechkit.params import MechanismParams
from mechkit.registry import get_spec

Inputs = Mapping[str, float] | Sequence[float] | np.ndarray

#: Closure solvers of `Mechanism.assemble`.
ASSEMBLY_METHODS = ("newton", "lm")
#: Methods of `Mechanism.forward_dynamics`.
FORWARD_METHODS = ("proximal", "kkt")
#: Redundancy resolutions of `Mechanism.inverse_dynamics`.
DISTRIBUTIONS = ("min_norm", "min_effort")


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
        dynamics.check_body_masses(self.model)
        self.data = self.model.createData()
        self.closures = parse_loops(urdf)
        self.cuts = [cut_rows(self.model, c) for c in self.closures]
        self.rows = ClosureRows(self.model, self.cuts)
        self.full_rows = ClosureRows(self.model, [cut_rows(self.model, c, "spatial") for c in self.closures])
        self.actuated = spec.actuated_joints(params)
        for joint in self.actuated:
            self._joint_id(joint)
        self._id_problem = dynamics.InverseDynamicsProblem(
            self.model, self.model.createData(), self.rows, self.full_rows,
            np.array([self.v_index(j) for j in self.actuated], dtype=int), self.actuated)
        self._pin_constraints: tuple | None = None
        self._pin_baumgarte = (0.0, 0.0)
        self._kkt_rows: np.ndarray | None = None
        self._delassus: float | None = None
        self.independent_rows = self.rows.size
        self.home_q = self.assemble(spec.home(params))
        self.independent_rows = kinematics.mobility(self.rows, self.data, self.home_q).rank

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
        return pin.neutral(self.model)

    def _inputs(self, inputs: Inputs | None, default_names: Sequence[str], arg: str = "inputs") -> dict[str, float]:
        if inputs is None:
            return {}
        return arguments.joint_values(arg, inputs, default_names, list(self.model.names[1:]))

    def _state(self, **values: Any) -> list[np.ndarray]:
        """Check state arrays by name (q: nq, v/a/tau: nv), (n,) or (N, n); see `arguments.state`."""
        sizes = {"q": self.model.nq, "v": self.model.nv, "a": self.model.nv, "tau": self.model.nv}
        return arguments.state(sizes, **values)

    def _input_names(self, inputs: Sequence[str] | None) -> list[str]:
        """The given input joints (default: the actuated ones), checked."""
        return list(self.actuated) if inputs is None else arguments.joint_names("inputs", inputs, list(self.model.names[1:]))

    def _split(self, names: Sequence[str]) -> tuple[np.ndarray, np.ndarray]:
        input_v = np.array([self.v_index(j) for j in names], dtype=int)
        free_v = np.setdiff1d(np.arange(self.model.nv), input_v)
        return input_v, free_v

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
        arguments.option("method", method, ASSEMBLY_METHODS)
        max_iter = arguments.integer("max_iter", max_iter, minimum=1)
        given = self._inputs(inputs, self.actuated)
        if guess is None and self.spec.guess is not None:
            guess = self.spec.guess(self.params)
        if guess is None or isinstance(guess, Mapping):
            q0 = self.neutral()
            for joint, value in self._inputs(guess, (), "guess").items():
                q0[self.q_index(joint)] = value
        else:
            q0 = arguments.array("guess", guess, self.model.nq, batch=False)
        for joint, value in given.items():
            q0[self.q_index(joint)] = value
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

    def velocities(self, q: np.ndarray, input_rates: Inputs, inputs: Sequence[str] | None = None, *,
                   allow_singular: bool = False) -> kinematics.Conditioned:
        """Joint velocities v from the input rates (rad/s or m/s), J v = 0; `v.condition` is the passive
        block's condition number.

        Args:
            allow_singular: return results where the passive block is below what the closure resolves
                (see `kinematics.resolvable_singular_value`) instead of raising.

        Batched: q of shape (N, nq) and rates of shape (N, k) (or joint name -> (N,) values) give (N, nv).

        Raises:
            SingularConfiguration: the inputs do not determine the motion at q (to what the closure resolves).
        """
        allow_singular = arguments.flag("allow_singular", allow_singular)
        q, = self._state(q=q)
        names = self._input_names(inputs)
        if batch.is_batch(q):
            q = batch.sample_array(q, "q", len(q), self.model.nq)
            keys, rates = batch.sample_inputs(input_rates, names, len(q))
            return np.array([self.velocities(qi, ri, keys, allow_singular=allow_singular)
                             for qi, ri in zip(q, rates)]).reshape(len(q), self.model.nv)
        rates = self._inputs(input_rates, names, "input_rates")
        input_v, free_v = self._split(list(rates))
        J = self.closure_jacobian(q)
        return kinematics.project_velocity(J, np.array(list(rates.values())), input_v, free_v, self.independent_rows,
                                           residual=self._residual_norm(), allow_singular=allow_singular)

    def accelerations(self, q: np.ndarray, v: np.ndarray, input_accelerations: Inputs,
                      inputs: Sequence[str] | None = None, *, allow_singular: bool = False) -> kinematics.Conditioned:
        """Joint accelerations a from the input accelerations, J a + gamma = 0 (batched like `velocities`;
        `allow_singular` and `a.condition` as in `velocities`)."""
        allow_singular = arguments.flag("allow_singular", allow_singular)
        q, v = self._state(q=q, v=v)
        names = self._input_names(inputs)
        if batch.is_batch(q):
            q = batch.sample_array(q, "q", len(q), self.model.nq)
            keys, acc = batch.sample_inputs(input_accelerations, names, len(q))
            v = batch.sample_array(v, "v", len(q), self.model.nv)
            return np.array([self.accelerations(qi, vi, ai, keys, allow_singular=allow_singular)
                             for qi, vi, ai in zip(q, v, acc)]).reshape(len(q), self.model.nv)
        acc = self._inputs(input_accelerations, names, "input_accelerations")
        input_v, free_v = self._split(list(acc))
        J = self.closure_jacobian(q)
        residual = self._residual_norm()
        gamma = self.closure_drift(q, v)
        return kinematics.project_velocity(J, np.array(list(acc.values())), input_v, free_v, self.independent_rows,
                                           rhs=gamma, residual=residual, allow_singular=allow_singular)

    def _residual_norm(self) -> float:
        """Closure residual norm at the configuration `self.data` holds (frames current)."""
        return float(np.linalg.norm(self.rows.residual(self.data)))

    def _check_regular(self, q: np.ndarray) -> None:
        """Raise `SingularConfiguration` where the actuated inputs do not determine the motion at q (or at
        any sample of a (N, nq) q), to what the closure resolves."""
        _, free_v = self._split(list(self.actuated))
        for qi in np.atleast_2d(q):
            s = np.linalg.svd(self.closure_jacobian(qi)[:, free_v], compute_uv=False)
            kinematics.judge_passive(s, self.independent_rows, self._residual_norm())

    def mobility(self, q: np.ndarray | None = None) -> kinematics.Mobility:
        """Numerical DOF and redundant constraints at q (default: the home assembly)."""
        q, = self._state(q=self.home_q if q is None else q)
        return kinematics.mobility(self.rows, self.data, q)

    def singularity(self, q: np.ndarray, inputs: Sequence[str] | None = None) -> float:
        """Condition number of the passive block of the closure Jacobian (inf: singular)."""
        q, = self._state(q=q)
        _, free_v = self._split(self._input_names(inputs))
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
            mu: proximal regularisation relative to the model's Delassus scale
                (`dynamics.delassus_scale` at the home assembly): dimensionless, so a model of any mass
                or size gets the same relative regularisation.
            accuracy: the proximal iterations' accuracy on the closure accelerations (m/s^2 for
                position rows; passed to Pinocchio as a multiplier accuracy, divided by the Delassus scale).
            max_iter: the proximal iterations' cap.

        Raises:
            ClosureNotConverged: the result violates J a + gamma = 0 beyond `dynamics.ACCELERATION_TOL`
                (e.g. too few proximal iterations for the mu given); it is never returned.
            SingularConfiguration: no unique accelerations (dependent rows, a coordinate without inertia).

        Batched: q (N, nq), v and tau (N, nv) give a result whose arrays have that leading axis.

        The two methods agree on the closure manifold (e = 0, J v = 0). Off it they differ: each
        method measures the closure error its own way (Pinocchio: point anchors in frame_a's local
        frame; KKT: the rows of `mechkit.closures`), so drift is corrected along different paths.
        """
        arguments.option("method", method, FORWARD_METHODS)
        q, v, tau = self._state(q=q, v=v, tau=tau)
        mu = arguments.number("mu", mu, minimum=0.0)
        accuracy = arguments.number("accuracy", accuracy, positive=True)
        max_iter = arguments.integer("max_iter", max_iter, minimum=1)
        if baumgarte is not None:
            baumgarte = tuple(arguments.array("baumgarte", baumgarte, 2, batch=False))
        if batch.is_batch(q):
            n = len(q)
            out = [self.forward_dynamics(qi, vi, ti, method, mu=mu, accuracy=accuracy, max_iter=max_iter,
                                         baumgarte=baumgarte) for qi, vi, ti in zip(q, v, tau)]
            return dynamics.ForwardDynamicsResult(np.array([r.a for r in out]).reshape(n, -1),
                                                  np.array([r.constraint_force for r in out]).reshape(n, -1))
        if method == "proximal":
            cms, cds = self.pin_constraints()
            gains = (0.0, 0.0) if baumgarte is None else tuple(baumgarte)
            if gains != self._pin_baumgarte:
                for cm in cms:
                    cm.setBaumgarteCorrectorParameters(pin.BaumgarteCorrectorParameters(*gains))
                self._pin_baumgarte = gains
            if self._delassus is None:
                self._delassus = dynamics.delassus_scale(pin.crba(self.model, self.data, self.home_q),
                                                         self.closure_jacobian(self.home_q))
            # Pinocchio tests its iterations on the multipliers (N): accuracy in m/s^2 times 1/Delassus
            prox = pin.ProximalSettings(accuracy / self._delassus, mu * self._delassus, max_iter)
            data = self._pin_data
            a = pin.constraintDynamics(self.model, data, q, v, tau, cms, cds, prox).copy()
            if not np.all(np.isfinite(a)):
                raise SingularConfiguration(float("inf"), f"pin.constraintDynamics returned non-finite accelerations (mu={mu})")
            result = dynamics.ForwardDynamicsResult(a, pin.rnea(self.model, data, q, v, a) - tau)
            J = self.closure_jacobian(q)
            # off the closure manifold Pinocchio's point anchors and our rows differ (see below): ours judge on it
            if dynamics.on_manifold(J, self.rows.residual(self.data), v):
                dynamics.check_closure_acceleration(J, a, self.closure_drift(q, v), 0.0, "forward dynamics (proximal)")
        else:  # "kkt"
            J = self.closure_jacobian(q)
            gamma = self.closure_drift(q, v)
            if baumgarte is not None:
                kp, kd = baumgarte
                gamma = gamma + kd * (J @ v) + kp * self.rows.residual(self.data)
            try:
                result = dynamics.kkt_forward(self.model, self.data, q, v, tau, J, gamma, self._independent_rows())
            except SingularConfiguration:  # the cached rows lost rank here: choose rows at this q
                result = dynamics.kkt_forward(self.model, self.data, q, v, tau, J, gamma)
        return result

    def _independent_rows(self) -> np.ndarray:
        """Independent closure rows at the home assembly (cached; KKT rows and the closure check's)."""
        if self._kkt_rows is None:
            self._kkt_rows = dynamics.independent_rows(self.closure_jacobian(self.home_q))
        return self._kkt_rows

    def inverse_dynamics(self, q: np.ndarray, v: np.ndarray, a: np.ndarray, fext=None, determinacy: bool = True,
                         distribution: str = "min_norm", *, allow_singular: bool = False,
                         ) -> dynamics.InverseDynamicsResult | batch.BatchInverseDynamicsResult:
        """Constrained RNEA: actuator efforts and the reaction of every joint (tree and cut).

        Reactions: the wrench parent side -> child side at the joint origin, world frame; see
        `dynamics.JointReaction` for the determinacy flags and `dynamics.inverse_dynamics` for
        `fext` (Pinocchio local-frame forces per joint) and `distribution` (redundant actuation).
        Batched: q (N, nq), v and a (N, nv), fext None, (N, njoints, 6) or N per-sample values give
        a `batch.BatchInverseDynamicsResult`.
        At a configuration where the actuators' passive block is below what the closure resolves the
        efforts are not determined: `SingularConfiguration`, unless `allow_singular`.
        """
        arguments.option("distribution", distribution, DISTRIBUTIONS)
        determinacy = arguments.flag("determinacy", determinacy)
        q, v, a = self._state(q=q, v=v, a=a)
        if not arguments.flag("allow_singular", allow_singular):
            self._check_regular(q)
        if batch.is_batch(q):
            n, p = len(q), self._id_problem
            out = [dynamics.inverse_dynamics(p, qi, vi, ai, fi, determinacy, distribution)
                   for qi, vi, ai, fi in zip(q, v, a, batch.sample_fext(fext, n, self.model.njoints))]
            return batch.stack_inverse(out, p.joint_names, p.actuated_names)
        fext = arguments.external_forces("fext", fext, self.model.njoints)
        return dynamics.inverse_dynamics(self._id_problem, q, v, a, fext, determinacy, distribution)


def load(name: str, **params: Any) -> Mechanism:
    """Build a registered mechanism from its parameters (unknown names raise `InvalidParameters`)."""
    if not isinstance(name, str):
        raise InvalidArgument("name", name, "expected a mechanism name (a string)")
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
    if not isinstance(urdf, str) or not urdf.strip():
        raise InvalidArgument("urdf", urdf, "expected URDF text (a non-empty string)")
    if not isinstance(name, str):
        raise InvalidArgument("name", name, "expected a string")
    if guess is not None and not isinstance(guess, Mapping):
        raise InvalidArgument("guess", guess, "expected a mapping joint name -> value")
    model = build_model(urdf)
    if actuated is not None:
        arguments.joint_names("actuated", actuated, list(model.names[1:]), allow_empty=True)
    joints = tuple(actuated) if actuated is not None else tuple(model.names[1:])
    spec = MechanismSpec(name=name, params=MechanismParams, template="", actuated=joints,
                         gruebler_dof=model.nv, home=lambda p: {}, guess=(lambda p: guess) if guess else None,
                         summary=f"loaded from URDF ({name})")
    return Mechanism(spec, MechanismParams(), urdf)
