"""The 2-DOF spherical platform's own methods in `mechkit bench` (`SPEC.bench_methods`, `SPEC.bench_references`).

Assembly: the paper's iterative FK and Newton on eq. (7), each from the home attitude, then the tree
joints in closed form. Inverse kinematics: the motor angles by eq. (8) from the platform's attitude
(the Hooke joint's roll and pitch). Inverse dynamics: the SOC decomposition (numpy), also the
independent reference.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from mechkit.catalog.contract import BenchFunction, BenchMethod, BenchReference
from mechkit.mechanisms.spherical_2dof import soc
from mechkit.mechanisms.spherical_2dof.fk import solve_fk
from mechkit.mechanisms.spherical_2dof.joint_state import tree_q
from mechkit.mechanisms.spherical_2dof.kinematics import BRANCHES, inverse_kinematics
from mechkit.validation.soc import SOCResult

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = ["METHODS", "REFERENCES", "fk_assembly", "ik_eq8", "soc_inverse_dynamics"]

HOOKE = ("hooke_roll", "hooke_pitch")


def fk_assembly(method: str) -> BenchFunction:
    """Assembly by an FK method of `fk.solve_fk` ("paper" or "newton") from home, then the tree.

    Args:
        method: "paper" or "newton".

    Returns:
        The bench function (mechanism, sample) -> q (nq,).
    """

    def run(mech: Mechanism, sample: Any) -> np.ndarray:
        phi = solve_fk(mech, method, sample.inputs, np.zeros(2)).phi
        return tree_q(mech, phi, sample.inputs)

    return run


def ik_eq8(mech: Mechanism, sample: Any) -> np.ndarray:
    """The motor angles (r11, r21) (rad) by the paper's eq. (8) from the sample's roll and pitch.

    Args:
        mech: the platform.
        sample: a bench sample (q with roll and pitch, v, a; the motor angles as inputs).

    Returns:
        (2,) motor angles, rad.
    """
    return inverse_kinematics(mech.params, [sample.q[mech.q_index(j)] for j in HOOKE], BRANCHES)


def soc_inverse_dynamics(mech: Mechanism, sample: Any) -> SOCResult:
    """SOC virtual work (numpy), every joint's moment about O.

    Args:
        mech: the platform.
        sample: a bench sample (q with roll and pitch, v, a; the motor angles as inputs).

    Returns:
        Motor torques (N m) and every joint's reaction.
    """
    hooke = [mech.v_index(j) for j in HOOKE]
    phi = [sample.q[mech.q_index(j)] for j in HOOKE]
    return soc.solve(mech.params, phi, sample.v[hooke], sample.a[hooke], BRANCHES)


METHODS = (
    BenchMethod("paper FK (Newton on IK eq. 8)", "assembly", fk_assembly("paper")),
    BenchMethod("Newton FK on eq. (7)", "assembly", fk_assembly("newton")),
    BenchMethod("IK eq. (8)", "inverse_kinematics", ik_eq8),
    BenchMethod("SOC (numpy)", "inverse_dynamics", soc_inverse_dynamics),
)
REFERENCES = (
    BenchReference("SOC virtual work (numpy), every joint's moment about O.", "inverse_dynamics", soc_inverse_dynamics),
)
