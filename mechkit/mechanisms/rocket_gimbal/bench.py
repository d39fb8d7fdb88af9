"""The engine gimbal's own methods in `mechkit bench` (`SPEC.bench_methods`, `SPEC.bench_references`).

Assembly: the paper's FK, (alpha, beta) by the resultant or by Newton on the lengths, then the servos'
Hooke angles and strokes in closed form. Inverse kinematics: the strokes in closed form from the
hinge angles (alpha, beta). Inverse dynamics: the SOC decomposition (numpy) with the analytic motion
and no thrust (the bench applies none), also the independent reference.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from mechkit.catalog.contract import BenchFunction, BenchMethod, BenchReference
from mechkit.mechanisms.rocket_gimbal.body_motion import gimbal_motion
from mechkit.mechanisms.rocket_gimbal.joint_state import hinges, joint_state
from mechkit.mechanisms.rocket_gimbal.kinematics import fk_newton, strokes
from mechkit.mechanisms.rocket_gimbal.params import geometry
from mechkit.mechanisms.rocket_gimbal.resultant import fk_resultant, pick_in_range
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene
from mechkit.mechanisms.rocket_gimbal.soc import soc_skcs
from mechkit.validation.soc import SOCResult, solve_soc

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = ["METHODS", "REFERENCES", "closed_form_strokes", "fk_assembly", "soc_inverse_dynamics"]


def fk_assembly(method: str) -> BenchFunction:
    """Assembly by the paper's FK ("resultant": in-range root of the resultant; else Newton from the
    null pose), then the servos' Hooke angles and strokes in closed form.

    Args:
        method: "resultant" (the paper's polynomial) or "newton".

    Returns:
        The bench function (mechanism, sample) -> q (nq,).
    """

    def assemble(mech: Mechanism, sample: Any) -> np.ndarray:
        geo, stroke = geometry(mech.params), np.asarray(sample.inputs, dtype=float)
        if method == "resultant":
            mode = pick_in_range(fk_resultant(geo, stroke))
            angles = np.array([mode.alpha, mode.beta])
        else:
            angles = fk_newton(geo, stroke)
        return joint_state(mech, gimbal_motion(geo, angles, np.zeros(2), np.zeros(2)))[0]

    return assemble


def closed_form_strokes(mech: Mechanism, sample: Any) -> np.ndarray:
    """Inverse kinematics in closed form: the strokes (dlA, dlB) (m) of the sample's hinge angles.

    Args:
        mech: the gimbal.
        sample: a bench sample (q with the hinge angles, v, a).

    Returns:
        (2,) strokes, m.
    """
    return strokes(geometry(mech.params), *hinges(mech, sample.q, "q"))


def soc_inverse_dynamics(mech: Mechanism, sample: Any) -> SOCResult:
    """SOC virtual work (numpy) with the analytic motion of (alpha, beta); no thrust (as the bench).

    Args:
        mech: the gimbal.
        sample: a bench sample (q with the hinge angles, v, a).

    Returns:
        Efforts (N) and every joint's reaction (world wrenches (6,)).
    """
    motion = gimbal_motion(
        geometry(mech.params), hinges(mech, sample.q, "q"), hinges(mech, sample.v), hinges(mech, sample.a)
    )
    return solve_soc(soc_skcs(mech.params, motion, SwingScene(thrust=0.0)))


METHODS = (
    BenchMethod("paper FK: resultant + closed-form servos", "assembly", fk_assembly("resultant")),
    BenchMethod("Newton FK on the lengths + closed-form servos", "assembly", fk_assembly("newton")),
    BenchMethod("IK closed form (servo lengths)", "inverse_kinematics", closed_form_strokes),
    BenchMethod("SOC (numpy)", "inverse_dynamics", soc_inverse_dynamics),
)
REFERENCES = (
    BenchReference(
        "SOC virtual work (numpy) with the analytic motion of (alpha, beta); no thrust (as the bench).",
        "inverse_dynamics",
        soc_inverse_dynamics,
    ),
)
