"""`MechanismClosure`: a mechanism's joints by name and its closure at one configuration.

The base of `mechkit.Mechanism` (which sets the attributes it reads): joint ids, indices and values by
name, the arguments a user gives checked and converted (joint names, values of any joint type, state
arrays of one sample or of N), the assembly that closes every loop, the closure rows' residual,
Jacobian and drift, the mobility and the singularity measure; one core function per quantity.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit import actuator_names, core
from mechkit.base import arguments, joint_arguments
from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.contract import MechanismSpec
from mechkit.catalog.params import MechanismParams

Inputs = Mapping[str, float | Sequence[float]] | Sequence[float] | np.ndarray


class MechanismClosure:
    """Joints by name and the closure of a mechanism; `mechkit.Mechanism` builds it and sets its attributes.

    Attributes:
        spec: the registry entry (its default assembly guess).
        params: the parameter values used.
        model: the Pinocchio model of the tree.
        closure_model: the tree with its closures, couplings and actuation (`mechkit.core.ClosureModel`).
        closure_data: its scratch data.
        actuated: the actuators, in effort order.
        home_mobility: the mobility at the home assembly.
    """

    spec: MechanismSpec
    params: MechanismParams
    model: pin.Model
    closure_model: core.ClosureModel
    closure_data: Any
    actuated: tuple[str, ...]
    home_mobility: core.Mobility
    _nq: int
    _nv: int

    # ---------------------------------------------------------------- joints by name
    def joint_id(self, joint: str) -> int:
        """Pinocchio id of a joint.

        Args:
            joint: the joint's name.

        Returns:
            Its id in `model` (1 for the first joint; 0 is the universe).

        Raises:
            InvalidParameters: no such joint (the message names the joints).
        """
        return self.closure_model.joint_id(joint)

    def q_index(self, joint: str) -> int:
        """Index of a joint's first coordinate in q.

        Args:
            joint: the joint's name.

        Returns:
            The index into q (nq,).
        """
        return self.model.joints[self.joint_id(joint)].idx_q

    def v_index(self, joint: str) -> int:
        """Index of a joint's first velocity coordinate in v.

        Args:
            joint: the joint's name.

        Returns:
            The index into v, a and tau (nv,).
        """
        return self.model.joints[self.joint_id(joint)].idx_v

    def neutral(self) -> np.ndarray:
        """Pinocchio's neutral configuration (nq,) of the tree (every joint at zero; loops open)."""
        return pin.neutral(self.model)

    def joint_values(self, q: np.ndarray) -> dict[str, float | np.ndarray]:
        """Every joint's value at a configuration.

        Args:
            q: (nq,) the configuration.

        Returns:
            Joint name -> value (rad or m; a ball joint's rotation vector (3,), see `mechkit.core.joints`).
        """
        return core.joint_values(self.model, q)

    def require_actuators(self, what: str) -> None:
        """Refuse a computation that needs actuators on a mechanism that declares none.

        Args:
            what: the computation, named in the error.

        Raises:
            InvalidParameters: the mechanism is unactuated.
        """
        if not self.actuated:
            raise InvalidParameters(
                "actuated",
                (),
                f"{self.spec.name} is unactuated (its file declares no "
                f"<transmission>, name_mot or MJCF actuator): {what} needs actuators; "
                "pass actuated=[...] (command line: --actuated J1,J2)",
            )

    def _values(self, values: Inputs | None, names: Sequence[str], arg: str) -> dict[str, Any]:
        """Joint values by name (a mapping, or values in the order of `names`), checked."""
        if values is None:
            return {}
        if not isinstance(values, Mapping) and not names:
            self.require_actuators(f"{arg} given in actuated order")
        sizes = {n: core.joint_size(self.model, self.joint_id(n)) for n in names if self.model.existJointName(n)}
        aliases = self._aliases
        known = actuator_names.known_names(self.closure_model, aliases)
        if isinstance(values, Mapping):
            actuator_names.check_known(self.closure_model, arg, values, aliases)
        return actuator_names.to_joints(
            self.closure_model, arg, joint_arguments.joint_values(arg, values, names, known, sizes), aliases
        )

    def _names(self, inputs: Sequence[str] | None, what: str) -> list[str]:
        """The given input joints or actuators (default: the actuated ones, which must exist), checked."""
        if inputs is None:
            self.require_actuators(what)
            return list(self.actuated)
        actuator_names.check_known(self.closure_model, "inputs", inputs, self._aliases)
        return joint_arguments.joint_names(
            "inputs", inputs, actuator_names.known_names(self.closure_model, self._aliases)
        )

    def _joints(self, names: Sequence[str]) -> list[str]:
        """The joints that input names (joints or actuators, checked) fix."""
        return actuator_names.to_joint_names(self.closure_model, "inputs", names, self._aliases)

    @property
    def _aliases(self) -> dict[str, str]:
        """The URDF's transmission names -> the joints they drive (parsed once)."""
        if "_transmissions" not in self.__dict__:
            self._transmissions = actuator_names.transmission_names(getattr(self, "urdf", None))
        return self._transmissions

    def _one(self, **values: Any) -> list[np.ndarray]:
        """State arrays of one sample checked by name (q: nq; v, a, tau: nv)."""
        return arguments.sample(self._sizes, **values)

    def _many(self, **values: Any) -> list[np.ndarray]:
        """State arrays of N samples checked by name ((N, nq), (N, nv)), one N for all."""
        return arguments.samples(self._sizes, **values)

    @property
    def _sizes(self) -> dict[str, int]:
        return {"q": self._nq, "v": self._nv, "a": self._nv, "tau": self._nv}

    # ---------------------------------------------------------------- the closure
    def assemble(
        self,
        inputs: Inputs,
        guess: Inputs | np.ndarray | None = None,
        *,
        tol: float = core.CLOSURE_TOL,
        method: str = "newton",
        max_iter: int = 60,
        reference: np.ndarray | None = None,
    ) -> np.ndarray:
        """Configuration q (nq,) that closes every loop with the given joints at the given values, on the
        branch of a reference, bounded revolute angles wrapped into their limits (`assembly`'s q; the
        branch taken and the joints left outside their limits: `assembly`).

        Args:
            inputs: joint or actuator name -> value (rad or m; a ball joint's rotation vector), or values
                in `actuated` order.
            guess: full q, or joint name -> value, picking the assembly branch (see `assembly`).
            tol: closure residual to reach (m for position rows).
            method: "newton" (minimum-norm Gauss-Newton) or "lm" (Levenberg-Marquardt).
            max_iter: iteration cap.
            reference: (nq,) a closed configuration whose branch is kept (see `assembly`).

        Returns:
            (nq,) the assembled configuration.

        Raises:
            ClosureNotConverged: no assembly found near the guess.
        """
        return self.assembly(inputs, guess, tol=tol, method=method, max_iter=max_iter, reference=reference).q

    def assembly(
        self,
        inputs: Inputs,
        guess: Inputs | np.ndarray | None = None,
        *,
        tol: float = core.CLOSURE_TOL,
        method: str = "newton",
        max_iter: int = 60,
        reference: np.ndarray | None = None,
    ) -> core.Assembly:
        """The assembly with the given joints at the given values: its q, the branch it took (named by its
        reference) and the joints on loops it leaves outside their limits (a tree's joint outside its
        limits is the pose given, not a branch).

        The branch is a reference's, kept by continuation (`mechkit.core.continuation`): `reference`, else
        the guess when it is a full configuration closing every loop (the previous sample along a motion),
        else the home assembly when no guess is given. Where there is none, or its branch cannot be
        followed, Newton from the guess (the spec's: a file's keyframe 'home', qpos0 or `<mechkit:guess>`;
        else the joints' zero). Bounded revolute angles are then wrapped by whole turns into their limits.

        Args:
            inputs: joint or actuator name -> value (rad or m; a ball joint's rotation vector), or values
                in `actuated` order.
            guess: full q, or joint name -> value, picking the assembly branch (default: the spec's
                guess, else the neutral configuration).
            tol: closure residual to reach (m for position rows).
            method: "newton" (minimum-norm Gauss-Newton) or "lm" (Levenberg-Marquardt).
            max_iter: iteration cap.
            reference: (nq,) a closed configuration whose branch is kept.

        Returns:
            The assembly (`core.Assembly`: q (nq,), iterations, residual, branch, the loops' joints outside
            their limits by name).

        Raises:
            ClosureNotConverged: no assembly found near the guess.
        """
        tol = arguments.number("tol", tol, positive=True)
        arguments.option("method", method, core.ASSEMBLY_METHODS)
        max_iter = arguments.integer("max_iter", max_iter, minimum=1)
        given = self._values(inputs, self.actuated, "inputs")
        named = "the reference given" if reference is not None else None
        start = "the guess given"
        if guess is None:
            start = self.spec.pose or ("the spec's guess" if self.spec.guess is not None else "the joints' zero")
            if self.spec.guess is not None:
                guess = self.spec.guess(self.params)
        if guess is None or isinstance(guess, Mapping):
            q0 = self.neutral()
            for joint, value in self._values(guess, (), "guess").items():
                core.set_joint_value(self.model, q0, self.joint_id(joint), value)
        else:
            q0 = arguments.array("guess", guess, self.model.nq, batch=False)
            if reference is None and np.linalg.norm(self.closure_residual(q0)) <= tol:
                reference, named = q0.copy(), "the closed guess given"  # the previous sample: its branch kept
        for joint, value in given.items():
            core.set_joint_value(self.model, q0, self.joint_id(joint), value)
        split = self.closure_model.split(tuple(given))
        out = None
        if reference is None and start != "the guess given" and hasattr(self, "home_q"):
            reference, named = self.home_q, "the home assembly"
        if reference is not None:
            (reference,) = self._one(q=reference)
            out = core.continue_from(self.closure_model, self.closure_data, reference, q0, split, tol=tol)
        if out is None:
            out = core.assemble(
                self.closure_model, self.closure_data, q0, split, tol=tol, max_iter=max_iter, method=method
            )
            branch = f"Newton from {start}" + (f" ({named}'s branch could not be followed)" if named else "")
        else:
            branch = f"continued from {named}"
        q, outside = core.wrap_into_limits(self.model, out.q)
        on_loops = tuple(j for j in outside if self.joint_id(j) in self.closure_model.on_loops)
        return core.Assembly(q, out.iterations, out.residual, branch, on_loops)

    def solve_closure(
        self,
        q0: np.ndarray,
        fixed: Sequence[str],
        *,
        tol: float = core.CLOSURE_TOL,
        max_iter: int = 60,
        method: str = "newton",
    ) -> core.Assembly:
        """Close every loop from a full configuration, keeping some joints at their values there
        (`assemble` with a full start).

        Args:
            q0: (nq,) the start.
            fixed: the joints kept at q0's values (may be empty).
            tol: closure residual to reach (m for position rows).
            max_iter: iteration cap.
            method: "newton" (minimum-norm Gauss-Newton) or "lm" (Levenberg-Marquardt).

        Returns:
            The solved q (nq,), the iterations taken and the residual reached (`core.Assembly`).

        Raises:
            ClosureNotConverged: no assembly found near q0.
        """
        (q0,) = self._one(q=q0)
        arguments.option("method", method, core.ASSEMBLY_METHODS)
        split = self.closure_model.split(
            tuple(joint_arguments.joint_names("fixed", fixed, list(self.model.names[1:]), allow_empty=True))
        )
        return core.assemble(
            self.closure_model,
            self.closure_data,
            q0,
            split,
            tol=arguments.number("tol", tol, positive=True),
            max_iter=arguments.integer("max_iter", max_iter, minimum=1),
            method=method,
        )

    def closure_residual(self, q: np.ndarray) -> np.ndarray:
        """Residual of every kept closure row.

        Args:
            q: (nq,) the configuration.

        Returns:
            (rows,) the residuals (m for position rows, dimensionless for alignment rows, rad or m for
            couplings), rows in `cuts` order.
        """
        return core.closure_residual(self.closure_model, self.closure_data, *self._one(q=q))

    def closure_jacobian(self, q: np.ndarray) -> np.ndarray:
        """Jacobian of the kept closure rows, J with de/dt = J v.

        Args:
            q: (nq,) the configuration.

        Returns:
            (rows, nv) J.
        """
        return core.closure_jacobian(self.closure_model, self.closure_data, *self._one(q=q))

    def closure_drift(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The closure rows' drift gamma, with d2e/dt2 = J a + gamma.

        Args:
            q: (nq,) the configuration.
            v: (nv,) the joint velocities.

        Returns:
            (rows,) gamma(q, v).
        """
        return core.closure_drift(self.closure_model, self.closure_data, *self._one(q=q, v=v))

    def mobility(self, q: np.ndarray | None = None) -> core.Mobility:
        """Numerical degrees of freedom and redundant constraints, from the rank of the closure Jacobian.

        Args:
            q: (nq,) an assembled configuration (None: the home assembly).

        Returns:
            The mobility (`core.Mobility`: dof, rows, rank, redundant, singular values).
        """
        if q is None:
            return self.home_mobility
        return core.mobility(self.closure_model, self.closure_data, *self._one(q=q))

    def singularity(self, q: np.ndarray, inputs: Sequence[str] | None = None) -> float:
        """How close the inputs are to losing control of the motion.

        Args:
            q: (nq,) an assembled configuration.
            inputs: the given joints (default: the actuated ones); the others are the passive block.

        Returns:
            The condition number of the passive block of the closure Jacobian (inf: singular).
        """
        (q,) = self._one(q=q)
        split = self.closure_model.split(tuple(self._joints(self._names(inputs, "the singularity measure"))))
        return core.passive_condition(self.closure_model, self.closure_data, q, split)
