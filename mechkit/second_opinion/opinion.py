"""`SecondOpinion`: a mechanism's automatic SOC decomposition, found once, and its solve at any instant."""

from __future__ import annotations

import time

import numpy as np

from mechkit.base.exceptions import MethodUnavailable
from mechkit.mechanism import Mechanism
from mechkit.second_opinion.decomposition import SKC, decompose
from mechkit.second_opinion.instant import instant
from mechkit.second_opinion.solve import Opinion, plan, solve_instant
from mechkit.second_opinion.structure_graph import Structure, build_structure


class SecondOpinion:
    """Efforts and joint reactions of a mechanism by sequential SOC virtual work, with its SKCs found
    automatically (`mechkit.second_opinion.decomposition`) from its structure at the home assembly.

    Attributes:
        mechanism: the mechanism.
        structure: its structure graph (bodies, joints, reaction components, actuators).
        skcs: the SKCs in solve order.
        plans: what each SKC's solve needs (`mechkit.second_opinion.solve.Plan`: its rows, moving
            bodies, released, actuated and known joints).
        level: the decomposition's granularity (`mechkit.second_opinion.decomposition.decompose`).
        decompose_seconds: wall time (s) the structure graph and the decomposition took.

    Args:
        mechanism: a mechanism with at least one loop closure.
        level: the decomposition's granularity ("component", "body" or "skc": `decomposition.decompose`).

    Raises:
        MethodUnavailable: a mechanism without loop closures, or with joint couplings (mimic, gears,
            tendons), which the decomposition does not model.
    """

    def __init__(self, mechanism: Mechanism, level: str = "skc"):
        start = time.perf_counter()
        self.mechanism, self.level = mechanism, level
        cm = mechanism.closure_model
        if not mechanism.closures:
            raise MethodUnavailable(
                "second opinion",
                "the mechanism has no loop closure: its SOCs are its tree, whose "
                "constrained RNEA is Pinocchio's RNEA; nothing to cross-check",
            )
        if cm.couplings:
            raise MethodUnavailable(
                "second opinion",
                f"joint couplings ({', '.join(c.name for c in cm.couplings)}) are not part of the SOC decomposition",
            )
        self._data, self._closure_data = cm.model.createData(), cm.create_data()
        self.structure: Structure = build_structure(cm, mechanism.home_q)
        zero = np.zeros(cm.nv)
        home = instant(cm, self._closure_data, self._data, self.structure, mechanism.home_q, zero, zero)
        self.skcs: list[SKC] = decompose(self.structure, home, level)
        self.plans = plan(self.skcs, self.structure, tuple(s.joint for s in mechanism.springs.springs))
        self.decompose_seconds = time.perf_counter() - start

    def solve(self, q: np.ndarray, v: np.ndarray, a: np.ndarray) -> Opinion:
        """Efforts and reactions for a motion (q, v, a) that closes the loops (rad, m and rates).

        Args:
            q: configuration (nq,), loops closed.
            v: velocity (nv,), J v = 0.
            a: acceleration (nv,), J a + gamma = 0.

        Returns:
            Efforts (N m or N), every joint's reaction (world [f, m] at the joint point), and which values statics
                leaves free.
        """
        m = self.mechanism
        state = instant(
            m.closure_model, self._closure_data, self._data, self.structure, q, v, a, m.passive_forces(q, v)
        )
        return solve_instant(self.plans, self.structure, state)
