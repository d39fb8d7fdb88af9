"""`MechanismClosure`: a mechanism's closure: its home assembly, the assembly at given inputs, the
closure rows' residual, Jacobian and drift, the mobility and the singularity measure.

It holds the closure model with a data (scratch, shared with the mechanism's other parts) and reads
joints and arguments by name through a `JointNaming`; one core function per quantity.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mechkit import core
from mechkit.base import arguments, joint_arguments
from mechkit.catalog.contract import MechanismSpec
from mechkit.catalog.params import MechanismParams
from mechkit.mechanism_naming import Inputs, JointNaming


class MechanismClosure:
    """The closure of a mechanism, assembled at home on construction.

    Args:
        naming: the mechanism's joints by name (`JointNaming`).
        closure_model: the tree with its closures, couplings and actuation (`mechkit.core.ClosureModel`).
        closure_data: a data of it (scratch).
        spec: the registry entry (its home inputs and default assembly guess).
        params: the parameter values used.

    Attributes:
        home_assembly: the home assembly's record (the branch it took, the loops' joints it leaves outside
            their limits); home_q: its q (nq,).
        home_mobility: the mobility at home; independent_rows: its rank (the closure's generic rank).
        idle: body -> idle freedoms at home (`mechkit.core.idle_freedoms`: a rod spinning about its axis).

    Raises:
        ClosureNotConverged, SingularConfiguration: the home assembly cannot be found.
    """

    def __init__(
        self,
        naming: JointNaming,
        closure_model: core.ClosureModel,
        closure_data: Any,
        spec: MechanismSpec,
        params: MechanismParams,
    ):
        self.naming, self.closure_model, self.closure_data = naming, closure_model, closure_data
        self.model, self.spec, self.params = closure_model.model, spec, params
        self._home: np.ndarray | None = None  # the home assembly's branch: none yet, Newton from the guess
        self.home_assembly = self.assembly(spec.home(params))
        self.home_q = self._home = self.home_assembly.q
        self.home_mobility = core.mobility(closure_model, closure_data, self.home_q)
        self.independent_rows = self.home_mobility.rank
        self.idle = core.idle_freedoms(
            self.model,
            self.home_q,
            core.closure_jacobian(closure_model, closure_data, self.home_q),
            set(closure_model.on_loops),
            closure_model.rigid_groups,
        )

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
        else the joints' zero). Bounded revolute angles are then wrapped by whole turns into their limits;
        where Newton's assembly still leaves loop joints outside them, one inside them is sought
        (`core.seek_inside_limits`: the file's limits say which assembly it means), else they are named.

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
        given = self.naming.values(inputs, self.naming.actuated, "inputs")
        named = "the reference given" if reference is not None else None
        start = "the guess given"
        if guess is None:
            start = self.spec.pose or ("the spec's guess" if self.spec.guess is not None else "the joints' zero")
            if self.spec.guess is not None:
                guess = self.spec.guess(self.params)
        if guess is None or isinstance(guess, Mapping):
            q0 = self.naming.neutral()
            for joint, value in self.naming.values(guess, (), "guess").items():
                core.set_joint_value(self.model, q0, self.naming.joint_id(joint), value)
        else:
            q0 = arguments.array("guess", guess, self.model.nq, batch=False)
            if reference is None and np.linalg.norm(self.closure_residual(q0)) <= tol:
                reference, named = q0.copy(), "the closed guess given"  # the previous sample: its branch kept
        for joint, value in given.items():
            core.set_joint_value(self.model, q0, self.naming.joint_id(joint), value)
        split = self.closure_model.split(tuple(given))
        out = None
        if reference is None and start != "the guess given" and self._home is not None:
            reference, named = self._home, "the home assembly"
        if reference is not None:
            (reference,) = self.naming.one(q=reference)
            out = core.continue_from(self.closure_model, self.closure_data, reference, q0, split, tol=tol)
        newton = out is None
        if newton:
            out = core.assemble(
                self.closure_model, self.closure_data, q0, split, tol=tol, max_iter=max_iter, method=method
            )
            branch = f"Newton from {start}" + (f" ({named}'s branch could not be followed)" if named else "")
        else:
            branch = f"continued from {named}"
        q, outside = core.wrap_into_limits(self.model, out.q)
        on_loops = tuple(j for j in outside if self.naming.joint_id(j) in self.closure_model.on_loops)
        if on_loops and newton:  # a continued branch is the reference's; Newton's may not be the file's
            inside = core.seek_inside_limits(self.closure_model, self.closure_data, q, split, tol=tol)
            if inside is not None:
                return core.Assembly(
                    inside.q, out.iterations, inside.residual, f"{branch}, re-sought inside the limits"
                )
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
        (q0,) = self.naming.one(q=q0)
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
        return core.closure_residual(self.closure_model, self.closure_data, *self.naming.one(q=q))

    def closure_jacobian(self, q: np.ndarray) -> np.ndarray:
        """Jacobian of the kept closure rows, J with de/dt = J v.

        Args:
            q: (nq,) the configuration.

        Returns:
            (rows, nv) J.
        """
        return core.closure_jacobian(self.closure_model, self.closure_data, *self.naming.one(q=q))

    def closure_drift(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The closure rows' drift gamma, with d2e/dt2 = J a + gamma.

        Args:
            q: (nq,) the configuration.
            v: (nv,) the joint velocities.

        Returns:
            (rows,) gamma(q, v).
        """
        return core.closure_drift(self.closure_model, self.closure_data, *self.naming.one(q=q, v=v))

    def mobility(self, q: np.ndarray | None = None) -> core.Mobility:
        """Numerical degrees of freedom and redundant constraints, from the rank of the closure Jacobian.

        Args:
            q: (nq,) an assembled configuration (None: the home assembly).

        Returns:
            The mobility (`core.Mobility`: dof, rows, rank, redundant, singular values).
        """
        if q is None:
            return self.home_mobility
        return core.mobility(self.closure_model, self.closure_data, *self.naming.one(q=q))

    def singularity(self, q: np.ndarray, inputs: Sequence[str] | None = None) -> float:
        """How close the inputs are to losing control of the motion.

        Args:
            q: (nq,) an assembled configuration.
            inputs: the given joints (default: the actuated ones); the others are the passive block.

        Returns:
            The condition number of the passive block of the closure Jacobian (inf: singular).
        """
        (q,) = self.naming.one(q=q)
        split = self.closure_model.split(
            tuple(self.naming.input_joints(self.naming.input_names(inputs, "the singularity measure")))
        )
        return core.passive_condition(self.closure_model, self.closure_data, q, split)
