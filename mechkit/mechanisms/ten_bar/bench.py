"""The ten-bar's own methods in `mechkit bench` (`SPEC.bench_methods`, `SPEC.bench_references`).

Assembly: the closed form (circle intersections, numpy) and the patent's dimension reduction (the
three units solved in turn on reduced Pinocchio models), both from the motors' angles and the rocker
R5 (the passive DOF) of the sample. Forward and inverse dynamics: the patent's Lagrange equations of
the first kind in reference-point coordinates, and SOC virtual work over its nine SKCs (numpy). The
bench applies no spring (its efforts are the actuators'), so these methods use the linkage with an
R5 spring-damper of zero stiffness and damping. The numpy methods start from the link motion (the
sample's state in reference-point coordinates, cached in `sample.extra`): their times exclude that
conversion. The closed form and the Lagrange method are also the references (independent of
Pinocchio).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from mechkit.catalog.contract import BenchMethod, BenchReference
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar import kinematics as tk
from mechkit.mechanisms.ten_bar import soc as ts
from mechkit.mechanisms.ten_bar.lagrange_model import lagrange_linkage
from mechkit.mechanisms.ten_bar.params import MOTORS, PASSIVE
from mechkit.validation import lagrange

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = ["METHODS", "REFERENCES"]

#: The independent coordinates the ten-bar's own methods take: the motors, then the rocker.
INPUTS = (*MOTORS, PASSIVE)


def _inputs(mech: Mechanism, sample: Any) -> dict[str, float]:
    return {j: float(sample.q[mech.q_index(j)]) for j in INPUTS}


def _q(mech: Mechanism, angles: dict[str, float]) -> np.ndarray:
    q = np.zeros(mech.model.nq)
    for joint, value in angles.items():
        q[mech.q_index(joint)] = value
    return q


def closed_form(mech: Mechanism, sample: Any) -> np.ndarray:
    """Assembly by circle intersections (numpy), as a mechkit q (rad).

    Args:
        mech: the ten-bar.
        sample: a bench sample (inputs R1, R3, R5 with rates and accelerations; q, v, a; `extra` for the cache).

    Returns:
        q (nq,).
    """
    i = _inputs(mech, sample)
    return _q(mech, geo.pose(mech.params, i["R1"], i["R3"], i["R5"]).joint_angles())


def dimension_reduction(mech: Mechanism, sample: Any) -> np.ndarray:
    """Assembly by the patent's dimension reduction from the bench's guess (the units cached).

    Args:
        mech: the ten-bar.
        sample: a bench sample (inputs R1, R3, R5 with rates and accelerations; q, v, a; `extra` for the cache).

    Returns:
        q (nq,).
    """
    if "dimension_reduction" not in sample.extra:
        sample.extra["dimension_reduction"] = tk.DimensionReduction(mech)
    guess = {j: float(sample.extra["guess"][mech.q_index(j)]) for j in td.JOINT_ORDER}
    return _q(mech, sample.extra["dimension_reduction"].solve(_inputs(mech, sample), guess))


def link_motion(mech: Mechanism, sample: Any) -> tuple[Any, np.ndarray, np.ndarray, np.ndarray]:
    """(linkage with a spring of zero stiffness, q_L, qd_L, motor accelerations) of the sample; cached.

    Args:
        mech: the ten-bar.
        sample: a bench sample (inputs R1, R3, R5 with rates and accelerations; q, v, a; `extra` for the cache).

    Returns:
        (the Lagrange linkage, q_L, qd_L (3 per link), motor accelerations (rad/s^2)).
    """
    if "ten_bar_link_motion" not in sample.extra:
        linkage = lagrange_linkage(mech.params, lagrange.Spring(PASSIVE, 0.0, 0.0))
        qL, vL = td.lagrange_state(mech.params, sample.q, sample.v, mech)
        motor_acc = np.array([sample.a[mech.v_index(j)] for j in MOTORS])
        sample.extra["ten_bar_link_motion"] = (linkage, qL, vL, motor_acc)
    return sample.extra["ten_bar_link_motion"]


def lagrange_forward(mech: Mechanism, sample: Any) -> np.ndarray:
    """Forward dynamics by the Lagrange equations under the sample's motor torques, as joint accelerations.

    Args:
        mech: the ten-bar.
        sample: a bench sample (inputs R1, R3, R5 with rates and accelerations; q, v, a; `extra` for the cache).

    Returns:
        a (nv,), rad/s^2.
    """
    linkage, qL, vL, _ = link_motion(mech, sample)
    qdd = linkage.forward(qL, vL, [sample.tau[mech.v_index(j)] for j in MOTORS])
    relative = geo.relative_angles({b: qdd[3 * i + 2] for i, b in enumerate(geo.BODIES)})
    a = np.zeros(mech.model.nv)
    for joint, value in relative.items():
        a[mech.v_index(joint)] = value
    return a


def _wrenches(forces: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """In-plane pin forces (fx, fz) as world wrenches [f, m] (6,)."""
    return {j: np.array([f[0], 0.0, f[1], 0.0, 0.0, 0.0]) for j, f in forces.items()}


def lagrange_inverse(mech: Mechanism, sample: Any) -> dict[str, Any]:
    """The patent's A f = P at the sample's motor accelerations: motor torques and every pair's force.

    Args:
        mech: the ten-bar.
        sample: a bench sample (inputs R1, R3, R5 with rates and accelerations; q, v, a; `extra` for the cache).

    Returns:
        {"efforts": motor -> torque (N m), "reactions": pair -> world wrench (6,)}.
    """
    linkage, qL, vL, motor_acc = link_motion(mech, sample)
    sol = linkage.solve(qL, vL, motor_acc)
    return {"efforts": sol.efforts, "reactions": _wrenches(sol.forces)}


def soc_inverse(mech: Mechanism, sample: Any) -> dict[str, Any]:
    """SOC virtual work over the nine SKCs, with the link accelerations of the sample's motion.

    Args:
        mech: the ten-bar.
        sample: a bench sample (inputs R1, R3, R5 with rates and accelerations; q, v, a; `extra` for the cache).

    Returns:
        {"efforts": motor -> torque (N m), "reactions": pair -> world wrench (6,)}.
    """
    linkage, qL, vL, motor_acc = link_motion(mech, sample)
    if "ten_bar_link_acceleration" not in sample.extra:
        sample.extra["ten_bar_link_acceleration"] = linkage.solve(qL, vL, motor_acc).qdd
    efforts, forces, _ = ts.solve(linkage, qL, vL, sample.extra["ten_bar_link_acceleration"])
    return {"efforts": efforts, "reactions": _wrenches(forces)}


METHODS = (
    BenchMethod("closed form (circle intersections, numpy)", "assembly", closed_form),
    BenchMethod("dimension reduction (3 reduced Pinocchio units)", "assembly", dimension_reduction),
    BenchMethod("Lagrange first kind, forward (numpy, from link motion)", "forward_dynamics", lagrange_forward),
    BenchMethod("Lagrange first kind A f = P (numpy, from link motion)", "inverse_dynamics", lagrange_inverse),
    BenchMethod("SOC virtual work, 9 SKCs (numpy, from link motion)", "inverse_dynamics", soc_inverse),
)
REFERENCES = (
    BenchReference("closed form (circle intersections)", "assembly", closed_form),
    BenchReference("Lagrange first kind, forward (numpy)", "forward_dynamics", lagrange_forward),
    BenchReference("Lagrange first kind A f = P (numpy)", "inverse_dynamics", lagrange_inverse),
)
