"""Ten-bar kinematics two ways: the full closure solve, and the patent's dimension reduction.

The patent solves the linkage unit by unit: the five-bar (wall, l123, l27, l67, l56) first, then
the four-bar (l123, l27, l79, l910), then the six-bar loop (l123, l34, l48, l87 with R7 known),
each unit taking the joints already solved as known. Here each unit is a reduced Pinocchio model
(`pin.buildReducedModel`, every joint outside the unit locked) with its one loop cut, solved by the
core's closure solver for its two unknown joints. The locked joints outside a unit never change
its solution: the five-bar's are downstream of it, and the four-bar and six-bar are solved for
joint angles relative to l123, which do not depend on where l123 stands (R1 is locked at any value).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin

from mechkit import core

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism


@dataclass(frozen=True)
class Unit:
    """A basic unit of the dimension reduction: its joints, inputs (known) and cut."""

    name: str
    joints: tuple[str, ...]
    inputs: tuple[str, ...]
    cut: str

    @property
    def unknowns(self) -> tuple[str, ...]:
        """The unit's joints that are not inputs (solved for)."""
        return tuple(j for j in self.joints if j not in self.inputs)


UNITS = (
    Unit("five_bar", ("R1", "R2", "R5", "R6"), ("R1", "R5"), "R7a"),
    Unit("four_bar", ("R2", "R7b", "R9"), ("R2",), "R10"),
    Unit("six_bar", ("R2", "R3", "R4", "R8"), ("R2", "R3"), "R7c"),
)
"""The patent's order; every unit's inputs are mechanism inputs or unknowns of an earlier unit."""


class _ReducedUnit:
    """One unit as a reduced Pinocchio model with its one closure (a closure model of the core)."""

    def __init__(self, mechanism: Mechanism, unit: Unit):
        model = mechanism.model
        locked = [model.getJointId(n) for n in model.names[1:] if n not in unit.joints]
        self.unit = unit
        self.model = pin.buildReducedModel(model, locked, mechanism.home_q)
        closure = next(c for c in mechanism.closures if c.name == unit.cut)
        self.closure_model = core.ClosureModel(self.model, [closure])
        self.closure_data = self.closure_model.create_data()
        self.q_index = {j: self.model.joints[self.model.getJointId(j)].idx_q for j in unit.joints}
        self.split = self.closure_model.split(unit.inputs)

    def solve(self, known: Mapping[str, float], guess: Mapping[str, float], tol: float) -> dict[str, float]:
        q = pin.neutral(self.model)
        for j in self.unit.joints:
            q[self.q_index[j]] = known[j] if j in self.unit.inputs else guess[j]
        q = core.assemble(self.closure_model, self.closure_data, q, self.split, tol=tol).q
        return {j: float(q[self.q_index[j]]) for j in self.unit.unknowns}


class DimensionReduction:
    """The patent's sequential unit solves on reduced Pinocchio models.

    Args:
        mechanism: `mechkit.load("ten_bar", ...)`.
    """

    def __init__(self, mechanism: Mechanism):
        self.units = [_ReducedUnit(mechanism, u) for u in UNITS]

    def unit_model(self, name: str) -> pin.Model:
        """The reduced model of one unit ("five_bar", "four_bar", "six_bar").

        Args:
            name: "five_bar", "four_bar" or "six_bar".

        Returns:
            The Pinocchio model.
        """
        return next(u.model for u in self.units if u.unit.name == name)

    def solve(self, inputs: Mapping[str, float], guess: Mapping[str, float], tol: float = 1e-13) -> dict[str, float]:
        """Every tree-joint angle (rad) from R1, R3 (motors) and R5 (passive), unit after unit.

        Args:
            inputs: values of R1, R3, R5 (rad).
            guess: joint name -> value near the wanted branch (e.g. the previous instant).
            tol: closure residual of each unit (m).

        Returns:
            Joint name -> angle (rad).

        Raises:
            ClosureNotConverged: a unit cannot close.
        """
        known = {k: float(v) for k, v in inputs.items()}
        for unit in self.units:
            known.update(unit.solve(known, guess, tol))
        return known


def full_solve(mechanism: Mechanism, inputs: Mapping[str, float], guess: np.ndarray, tol: float = 1e-13) -> np.ndarray:
    """The whole closure at once (the core's Gauss-Newton on all 6 rows) from R1, R3, R5.

    Args:
        mechanism: the ten-bar.
        inputs: values of R1, R3, R5 (rad).
        guess: configuration (nq,) near the wanted branch.
        tol: closure residual to reach (m).

    Returns:
        q (nq,).
    """
    return mechanism.assemble(dict(inputs), guess=guess, tol=tol)
