"""What the core's functions return: mobility, forward and inverse dynamics results.

Reactions are the wrench [f (N), m (N m)] the parent side of a joint exerts on its child side, world
axes, moment about the joint origin; for a cut joint the parent side is frame_a's body and the point
is frame_b's origin. `determinate[i]` is False for a component static equilibrium does not fix
(redundant constraints): its value is then the chosen convention (minimum norm).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from mechkit.core.rank import ranks, singular_values


@dataclass(frozen=True)
class Mobility:
    """Numerical mobility at a configuration.

    Attributes:
        dof: nv - rank(J): degrees of freedom.
        rows: number of closure rows kept.
        rank: rank of the closure Jacobian.
        redundant: rows - rank: redundant constraints.
        singular_values: of the closure Jacobian, descending.
    """

    dof: int
    rows: int
    rank: int
    redundant: int
    singular_values: np.ndarray


class ForwardDynamicsResult:
    """Accelerations a (nv,) or (N, nv), the generalised constraint force J^T lambda of the same shape,
    and the iterations Pinocchio's proximal solver took ("proximal", "lcaba"; the largest over a batch;
    0 for the direct methods).

    Args:
        a: the accelerations (rad/s^2 or m/s^2).
        constraint_force: J^T lambda (N m or N), or None with `rows`.
        iterations: the solver's iterations.
        rows: (J (rows, nv), lambda (rows,)) from which J^T lambda is computed on first read (instead of
            `constraint_force`; neither is changed afterwards).
    """

    __slots__ = ("_force", "_rows", "a", "iterations")

    def __init__(
        self,
        a: np.ndarray,
        constraint_force: np.ndarray | None = None,
        iterations: int = 0,
        rows: tuple[np.ndarray, np.ndarray] | None = None,
    ):
        self.a, self.iterations, self._force, self._rows = a, iterations, constraint_force, rows

    @property
    def constraint_force(self) -> np.ndarray:
        """The generalised constraint force J^T lambda (N m or N)."""
        if self._force is None:
            J, lam = self._rows
            self._force, self._rows = lam.dot(J), None
        return self._force

    def __repr__(self) -> str:
        force, it = self.constraint_force, self.iterations
        return f"ForwardDynamicsResult(a={self.a!r}, constraint_force={force!r}, iterations={it})"


@dataclass(frozen=True)
class JointReaction:
    """One joint's reaction.

    Attributes:
        wrench: (6,) [f (N), m (N m)], world axes, about the joint origin (see the module docstring).
        determinate: (6,) bool, or None when the test was not run.
        support: True for joints to the ground.
    """

    wrench: np.ndarray
    determinate: np.ndarray | None
    support: bool


def condition_numbers(A: np.ndarray) -> np.ndarray:
    """Condition numbers s_max / s_rank of N matrices, rank by `mechkit.core.rank.ranks`.

    Args:
        A: (N, m, n) matrices.

    Returns:
        (N,) the condition numbers (nan for an empty matrix).
    """
    if not A.shape[1] or not A.shape[2]:
        return np.full(len(A), np.nan)
    s = singular_values(A)
    return s[:, 0] / s[np.arange(len(s)), np.maximum(ranks(s), 1) - 1]


class InverseDynamicsResult:
    """Constrained inverse dynamics of one sample; the dicts are built on first use.

    Attributes:
        joint_names: the reactions' joints (tree joints in model order, then the cut joints).
        actuated: the actuators, in effort order.
        effort_values: (na,) efforts (N m or N); reaction_values: (n_joints, 6) reactions.
        multipliers: (rows,) closure-row multipliers (J^T lambda is the generalised constraint force).
        condition: condition number of [S, J^T] (nan where it was not computed; with `system`, computed
            from it on first read).
        support: (n_joints,) True for joints to the ground.
        determinate: (n_joints, 6) or None; efforts_determinate_values: (na,) or None.
    """

    def __init__(
        self,
        joint_names: tuple[str, ...],
        actuated: tuple[str, ...],
        efforts: np.ndarray,
        reactions: np.ndarray,
        support: np.ndarray,
        multipliers: np.ndarray,
        condition: float,
        determinate: np.ndarray | None = None,
        efforts_determinate: np.ndarray | None = None,
        system: np.ndarray | None = None,
    ):
        self.joint_names, self.actuated = joint_names, actuated
        self.effort_values, self.reaction_values, self.support = efforts, reactions, support
        self.multipliers, self._condition, self._system = multipliers, condition, system
        self.determinate, self.efforts_determinate_values = determinate, efforts_determinate

    @property
    def condition(self) -> float:
        """Condition number s_max / s_rank of [S, J^T] (nan where it was not computed)."""
        if self._system is not None:  # by its singular values, on first read
            self._condition, self._system = float(condition_numbers(self._system[None])[0]), None
        return self._condition

    @cached_property
    def efforts(self) -> dict[str, float]:
        """Actuator name -> effort (N m or N)."""
        return dict(zip(self.actuated, self.effort_values.tolist()))

    @cached_property
    def reactions(self) -> dict[str, JointReaction]:
        """Joint name -> `JointReaction` (tree joints, then the cut joints)."""
        det = self.determinate
        return {
            name: JointReaction(self.reaction_values[j], None if det is None else det[j], bool(self.support[j]))
            for j, name in enumerate(self.joint_names)
        }

    @cached_property
    def efforts_determinate(self) -> dict[str, bool] | None:
        """Actuator name -> whether statics fixes its effort (False: redundant actuation; None: not tested)."""
        if self.efforts_determinate_values is None:
            return None
        return dict(zip(self.actuated, self.efforts_determinate_values.tolist()))


class BatchInverseDynamicsResult:
    """Constrained inverse dynamics of N samples.

    Attributes:
        joint_names: the reactions' joints (tree joints in model order, then the cut joints).
        actuated: the actuators, in effort order.
        efforts: (N, na) actuator efforts (N m or N).
        reactions: (N, n_joints, 6) reactions (see the module docstring).
        support: (n_joints,) True for joints to the ground.
        multipliers: (N, rows) closure-row multipliers.
        condition: (N,) condition number of [S, J^T] (nan where it was not computed; with `system`,
            computed from it on first read).
        determinate: (N, n_joints, 6) components fixed by statics, or None (test not run).
        efforts_determinate: (N, na) efforts fixed by statics, or None (test not run).
    """

    def __init__(
        self,
        joint_names: tuple[str, ...],
        actuated: tuple[str, ...],
        efforts: np.ndarray,
        reactions: np.ndarray,
        support: np.ndarray,
        multipliers: np.ndarray,
        condition: np.ndarray | None,
        determinate: np.ndarray | None = None,
        efforts_determinate: np.ndarray | None = None,
        system: np.ndarray | None = None,
    ):
        self.joint_names, self.actuated = joint_names, actuated
        self.efforts, self.reactions, self.support, self.multipliers = efforts, reactions, support, multipliers
        self._condition, self._system = condition, system
        self.determinate, self.efforts_determinate = determinate, efforts_determinate

    @property
    def condition(self) -> np.ndarray:
        """(N,) condition numbers s_max / s_rank of [S, J^T] (nan where they were not computed)."""
        if self._system is not None:  # by their singular values, on first read
            self._condition, self._system = condition_numbers(self._system), None
        return self._condition

    def __len__(self) -> int:
        return self.efforts.shape[0]

    def sample(self, i: int) -> InverseDynamicsResult:
        """Sample i as the single-sample result.

        Args:
            i: the sample's index.

        Returns:
            The single-sample result of sample i (its reactions' dicts built on first use).
        """
        det, eff = self.determinate, self.efforts_determinate
        return InverseDynamicsResult(
            self.joint_names,
            self.actuated,
            self.efforts[i],
            self.reactions[i],
            self.support,
            self.multipliers[i],
            float(self.condition[i]),
            None if det is None else det[i],
            None if eff is None else eff[i],
        )
