"""Batched inputs and results: many samples (a leading axis N) through the kinematics and dynamics.

`Mechanism.velocities`, `accelerations`, `forward_dynamics` and `inverse_dynamics` take q of shape
(N, nq) (and v, a, tau of shape (N, nv), input rates of shape (N, k) or a mapping of joint name ->
(N,) values) and return arrays with that leading axis. The inverse dynamics returns one
`BatchInverseDynamicsResult`: efforts (N, n_actuated), reactions (N, n_joints, 6) in `joint_names`
order, determinacy masks, multipliers.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters
from mechkit.core.dynamics import InverseDynamicsResult, JointReaction


@dataclass(frozen=True)
class BatchInverseDynamicsResult:
    """Constrained inverse dynamics of N samples.

    Attributes:
        joint_names: the reactions' joints (tree joints in model order, then the cut joints).
        actuated: the actuated joints, in effort order.
        efforts: (N, n_actuated) actuator efforts (N m or N).
        reactions: (N, n_joints, 6) wrench [f (N), m (N m)] the parent side exerts on the child side,
            world frame, moment about the joint origin (see `dynamics.JointReaction`).
        support: (n_joints,) True for joints to the ground.
        multipliers: (N, rows) closure-row multipliers.
        condition: (N,) condition number of [S, J^T] (nan on the fast square path).
        determinate: (N, n_joints, 6) components fixed by statics, or None (test not run).
        efforts_determinate: (N, n_actuated) efforts fixed by statics, or None (test not run).
    """

    joint_names: tuple[str, ...]
    actuated: tuple[str, ...]
    efforts: np.ndarray
    reactions: np.ndarray
    support: np.ndarray
    multipliers: np.ndarray
    condition: np.ndarray
    determinate: np.ndarray | None = None
    efforts_determinate: np.ndarray | None = None

    def __len__(self) -> int:
        return self.efforts.shape[0]

    def sample(self, i: int) -> InverseDynamicsResult:
        """Sample i as the single-sample result type."""
        det = self.determinate
        reactions = {name: JointReaction(self.reactions[i, j], None if det is None else det[i, j], bool(self.support[j]))
                     for j, name in enumerate(self.joint_names)}
        eff_det = None if self.efforts_determinate is None else dict(
            zip(self.actuated, self.efforts_determinate[i].tolist()))
        return InverseDynamicsResult(dict(zip(self.actuated, self.efforts[i].tolist())), reactions,
                                     self.multipliers[i], float(self.condition[i]), eff_det)


def is_batch(q: np.ndarray | Sequence[float]) -> bool:
    """True when q carries a leading sample axis (shape (N, nq))."""
    return np.ndim(q) == 2


def sample_array(x: np.ndarray | Sequence[Sequence[float]], name: str, n: int, width: int) -> np.ndarray:
    """x as an (n, width) float array, or `InvalidParameters` naming the argument."""
    arr = np.asarray(x, dtype=float)
    if n == 0:
        raise InvalidParameters(name, "0 samples", "a batch needs at least one sample")
    if arr.shape != (n, width):
        raise InvalidParameters(name, f"shape {arr.shape}", f"expected ({n}, {width}): one row per sample of q")
    return arr


def sample_inputs(values: np.ndarray | Mapping[str, np.ndarray | Sequence[float]], names: Sequence[str], n: int) -> tuple[list[str], np.ndarray]:
    """Batched input rates: (n, k) values in `names` order, or a mapping joint name -> (n,) values.

    Returns the joint names and an (n, k) array.
    """
    if isinstance(values, Mapping):
        keys = list(values)
        cols = [np.broadcast_to(np.asarray(values[k], dtype=float), (n,)) for k in keys]
        return keys, np.column_stack(cols) if cols else np.zeros((n, 0))
    return list(names), sample_array(values, "inputs", n, len(names))


def sample_fext(fext: np.ndarray | Sequence | None, n: int, njoints: int) -> list:
    """Per-sample external forces: None, an (n, njoints, 6) array of local-frame wrenches, or n per-sample values."""
    if fext is None:
        return [None] * n
    if isinstance(fext, np.ndarray):
        if fext.shape != (n, njoints, 6):
            raise InvalidParameters("fext", f"shape {fext.shape}", f"expected ({n}, {njoints}, 6) or {n} per-sample values")
        return [[pin.Force(w) for w in sample] for sample in fext]
    if len(fext) != n:
        raise InvalidParameters("fext", f"{len(fext)} values", f"expected one per sample ({n})")
    return list(fext)
