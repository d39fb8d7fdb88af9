"""Cross-checks of the engine gimbal: FK three ways, IK round trips, Pinocchio vs SOC inverse dynamics.

Used by the tests, by `mechkit report rocket_gimbal` (`self_checks`) and by the benchmark tool.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.mechanism import Mechanism
from mechkit.mechanisms.rocket_gimbal.joint_state import hinges, joint_state
from mechkit.mechanisms.rocket_gimbal.kinematics import (
    PAPER_EXAMPLE,
    RULE_STROKE,
    actuator_lengths,
    fk_newton,
    strokes,
)
from mechkit.mechanisms.rocket_gimbal.params import geometry
from mechkit.mechanisms.rocket_gimbal.resultant import fk_resultant, pick_in_range
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene, thrust_fext
from mechkit.mechanisms.rocket_gimbal.soc import soc_skcs
from mechkit.validation.soc import solve_soc

__all__ = [
    "DynamicsAgreement",
    "FKAgreement",
    "dynamics_agreement",
    "fk_agreement",
    "fk_closure",
    "self_checks",
]


def fk_closure(mech: Mechanism, stroke: np.ndarray, guess: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """FK by the closure solver (`Mechanism.assemble`, the strokes as inputs).

    Args:
        mech: the gimbal.
        stroke: (dlA, dlB), m.
        guess: the solve's start (nq,) (default: the home assembly).

    Returns:
        ((alpha, beta) rad, q (nq,)).
    """
    q = mech.assemble({"a_stroke": stroke[0], "b_stroke": stroke[1]}, guess=guess)
    return hinges(mech, q, "q"), q


@dataclass(frozen=True)
class FKAgreement:
    """Worst disagreements over a stroke grid.

    Attributes:
        polynomial_newton, polynomial_closure, newton_closure: max |d alpha|, |d beta| (rad).
        ik_round_trip: max |IK(FK(s)) - s| over the three methods (m).
        worst_condition: largest condition number of the in-range resultant root off the diagonal.
    """

    polynomial_newton: float
    polynomial_closure: float
    newton_closure: float
    ik_round_trip: float
    worst_condition: float


def fk_agreement(mech: Mechanism, n: int = 5, stroke_max: float = RULE_STROKE) -> FKAgreement:
    """FK by the resultant, by Newton and by the closure solver over an n x n grid of strokes.

    Args:
        mech: the gimbal.
        n: grid points per stroke axis.
        stroke_max: the grid's half width, m.

    Returns:
        The worst differences (rad) of each pair of methods, the IK round trip (m) and the worst condition.
    """
    geo = geometry(mech.params)
    axis = np.linspace(-stroke_max, stroke_max, n)
    worst = np.zeros(5)
    for sa in axis:
        for sb in axis:
            s = np.array([sa, sb])
            mode = pick_in_range(fk_resultant(geo, s))
            poly = np.array([mode.alpha, mode.beta])
            newton = fk_newton(geo, s)
            closure, _ = fk_closure(mech, s)
            trips = [np.abs(strokes(geo, *x) - s).max() for x in (poly, newton, closure)]
            cond = mode.condition if sa != sb else 0.0
            worst = np.maximum(
                worst,
                [
                    np.abs(poly - newton).max(),
                    np.abs(poly - closure).max(),
                    np.abs(newton - closure).max(),
                    max(trips),
                    cond,
                ],
            )
    return FKAgreement(*map(float, worst))


@dataclass(frozen=True)
class DynamicsAgreement:
    """Pinocchio constrained RNEA vs SOC over a swing.

    Attributes:
        efforts: max relative difference of the actuator forces.
        reactions: max over joints of |w_pin - w_soc|_inf / |w_pin|_inf.
        indeterminate: number of reaction components Pinocchio flags indeterminate (expected 0).
        consistency: max SOC consistency residual (over-determined SKCs).
        missing: joints Pinocchio reports that the SOC decomposition does not.
    """

    efforts: float
    reactions: float
    indeterminate: int
    consistency: float
    missing: tuple[str, ...]


def dynamics_agreement(
    mech: Mechanism, scene: SwingScene | None = None, times: np.ndarray | None = None
) -> DynamicsAgreement:
    """Inverse dynamics of the swing by Pinocchio (thrust as fext) and by SOC, compared at `times` (s).

    Args:
        mech: the gimbal.
        scene: the swing (default `SwingScene()`).
        times: the instants, s (default: one period).

    Returns:
        The worst relative differences of efforts and reactions, the indeterminate components, the SOC
            consistency, and the joints not compared.
    """
    scene = scene or SwingScene()
    times = np.linspace(0.0, 1.0 / scene.frequency, 7, endpoint=False) if times is None else times
    eff = rea = cons = 0.0
    indeterminate = 0
    missing: set[str] = set()
    for t in times:
        motion = scene.motion(mech.params, t)
        q, v, a = joint_state(mech, motion)
        pin_result = mech.inverse_dynamics(q, v, a, fext=thrust_fext(mech, q, scene))
        soc = solve_soc(soc_skcs(mech.params, motion, scene))
        for name, u in pin_result.efforts.items():
            eff = max(eff, abs(u - soc.efforts[name]) / abs(u))
        for joint, reaction in pin_result.reactions.items():
            indeterminate += int(np.count_nonzero(~reaction.determinate))
            if joint not in soc.reactions:
                missing.add(joint)
                continue
            scale = np.abs(reaction.wrench).max()
            rea = max(rea, np.abs(reaction.wrench - soc.reactions[joint]).max() / scale)
        cons = max(cons, *soc.consistency.values())
    return DynamicsAgreement(float(eff), float(rea), indeterminate, float(cons), tuple(sorted(missing)))


def self_checks(mech: Mechanism) -> dict[str, float]:
    """Rows of `mechkit report rocket_gimbal` (worst error of each check; smaller is better).

    Args:
        mech: the gimbal.

    Returns:
        Check name -> worst error.
    """
    geo = geometry(mech.params)
    fk = fk_agreement(mech, n=3)
    dyn = dynamics_agreement(mech, times=np.array([0.1, 0.35]))
    lengths = actuator_lengths(geo, *PAPER_EXAMPLE["angles"])
    return {
        "paper IK example vs printed lengths (m)": float(np.abs(lengths - PAPER_EXAMPLE["lengths"]).max()),
        "FK resultant vs Newton (rad)": fk.polynomial_newton,
        "FK resultant vs closure solver (rad)": fk.polynomial_closure,
        "IK of FK round trip (m)": fk.ik_round_trip,
        "efforts Pinocchio vs SOC (relative)": dyn.efforts,
        "reactions Pinocchio vs SOC (relative)": dyn.reactions,
        "SOC consistency residual (relative)": dyn.consistency,
    }
