"""The 2-DOF spherical platform's own methods in `mechkit bench` (`SPEC.bench_methods`, `SPEC.bench_references`).

Assembly: the paper's iterative FK and Newton on eq. (7), each from the home attitude, then the tree
joints in closed form. Inverse dynamics: the SOC decomposition (numpy), also the independent reference.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from mechkit.catalog.contract import BenchFunction, BenchMethod, BenchReference
from mechkit.mechanisms.spherical_2dof import soc
from mechkit.mechanisms.spherical_2dof.fk import solve_fk
from mechkit.mechanisms.spherical_2dof.kinematics import BRANCHES
from mechkit.mechanisms.spherical_2dof.tree import tree_q
from mechkit.validation.soc import SOCResult

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = ["METHODS", "REFERENCES", "fk_assembly", "soc_inverse_dynamics"]


def fk_assembly(method: str) -> BenchFunction:
    """Assembly by an FK method of `fk.solve_fk` ("paper" or "newton") from home, then the tree."""

    def run(mech: Mechanism, sample: Any) -> np.ndarray:
        phi = solve_fk(mech, method, sample.inputs, np.zeros(2)).phi
        return tree_q(mech, phi, sample.inputs)

    return run


def soc_inverse_dynamics(mech: Mechanism, sample: Any) -> SOCResult:
    """SOC virtual work (numpy), every joint's moment about O."""
    hooke = [mech.v_index("hooke_roll"), mech.v_index("hooke_pitch")]
    phi = [sample.q[mech.q_index("hooke_roll")], sample.q[mech.q_index("hooke_pitch")]]
    return soc.solve(mech.params, phi, sample.v[hooke], sample.a[hooke], BRANCHES)


METHODS = (
    BenchMethod("paper FK (Newton on IK eq. 8)", "assembly", fk_assembly("paper")),
    BenchMethod("Newton FK on eq. (7)", "assembly", fk_assembly("newton")),
    BenchMethod("SOC (numpy)", "inverse_dynamics", soc_inverse_dynamics),
)
REFERENCES = (
    BenchReference("SOC virtual work (numpy), every joint's moment about O.", "inverse_dynamics",
                   soc_inverse_dynamics),
)
