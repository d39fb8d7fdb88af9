"""Self-checks of the 2-DOF spherical platform along the cone scene (rows of `mechkit report`).

Each check compares independent methods and returns its worst error (smaller is better).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mechkit.mechanisms.spherical_2dof import kinematics as kin
from mechkit.mechanisms.spherical_2dof import soc
from mechkit.mechanisms.spherical_2dof.fk import METHODS, fk_newton, fk_paper, solve_fk
from mechkit.mechanisms.spherical_2dof.joint_state import state
from mechkit.mechanisms.spherical_2dof.kinematics import BRANCHES, platform_normal
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude, cone_times

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = [
    "cone_round_trip",
    "dynamics_agreement",
    "fk_agreement",
    "jacobian_fd_error",
    "self_checks",
]

#: Compared components of every reaction: the moments about O (world x, y, z). The forces at O
#: are statically indeterminate (the tests check that Pinocchio flags them so).
MOMENTS = [3, 4, 5]


def cone_round_trip(p: kin.Geometry, samples: int = 72) -> tuple[float, float]:
    """IK of the cone (eq. 8), then the paper's FK of those motor curves, tracking from home.

    Args:
        p: the structural parameters.
        samples: instants over one turn of the cone.

    Returns:
        (worst attitude error (rad), worst error of the unit normal's tip, the marker point (-)).
    """
    phi_plan = cone_attitude(cone_times(samples))[0]
    phi = np.zeros(2)  # P0: the calibrated home pose
    worst = np.zeros((samples, 2))
    for k, target in enumerate(phi_plan):
        theta = kin.inverse_kinematics(p, target, BRANCHES)
        phi = fk_paper(p, theta, phi, BRANCHES).phi
        worst[k] = phi - target
    normal = np.linalg.norm(platform_normal(phi_plan + worst) - platform_normal(phi_plan), axis=1)
    return float(np.abs(worst).max()), float(normal.max())


def jacobian_fd_error(p: kin.Geometry, samples: int = 12, h: float = 1e-5) -> float:
    """Worst |J - J_fd| (rad/rad): J = -B^-1 A against central differences of the FK (Newton) in theta.

    Args:
        p: the structural parameters.
        samples: attitudes along the cone.
        h: the finite-difference step, rad.

    Returns:
        The worst difference.
    """
    worst = 0.0
    for target in cone_attitude(cone_times(samples))[0]:
        theta = kin.inverse_kinematics(p, target, BRANCHES)
        fd = np.column_stack(
            [
                (fk_newton(p, theta + h * e, target).phi - fk_newton(p, theta - h * e, target).phi) / (2 * h)
                for e in np.eye(2)
            ]
        )
        worst = max(worst, float(np.abs(kin.jacobian(p, theta, target) - fd).max()))
    return worst


def fk_agreement(mech: Mechanism, samples: int = 12, offset: float = 0.05) -> float:
    """Worst pairwise difference (rad) of the three FK methods along the cone, started ``offset`` away.

    Args:
        mech: the platform.
        samples: attitudes along the cone.
        offset: the starts' distance from the answer, rad.

    Returns:
        The worst difference, rad.
    """
    worst = 0.0
    for target in cone_attitude(cone_times(samples))[0]:
        theta = kin.inverse_kinematics(mech.params, target, BRANCHES)
        found = [solve_fk(mech, m, theta, target + offset).phi for m in METHODS]
        worst = max(worst, max(float(np.abs(a - b).max()) for a in found for b in found))
    return worst


def dynamics_agreement(mech: Mechanism, samples: int = 24) -> dict[str, float]:
    """Motor torques and joint moments about O, Pinocchio (constrained RNEA) vs SOC, along the cone.

    The moment that a motor joint transmits includes the motor torque: SOC's r{i}1 reaction (the
    constraint part) plus ``effort * u_i``.

    Args:
        mech: the platform.
        samples: instants along the cone.

    Returns:
        Relative errors, worst |difference| over the scene / the scene's peak |value|:
        "efforts", "support" (hooke_roll), "joints" (every joint, worst); "consistency": the worst
        consistency residual of the over-determined SKCs. An error is inf if Pinocchio flags a
        compared component indeterminate (that would compare a convention, not physics).
    """
    t = cone_times(samples)
    phi, phi_d, phi_dd = cone_attitude(t)
    pin_u, soc_u = [], []
    pin_m, soc_m = {}, {}
    determinate, consistency = True, 0.0
    for k in range(samples):
        q, v, a = state(mech, phi[k], phi_d[k], phi_dd[k])
        ref = mech.inverse_dynamics(q, v, a)
        ours = soc.solve(mech.params, phi[k], phi_d[k], phi_dd[k], BRANCHES)
        consistency = max(consistency, *ours.consistency.values())
        pin_u.append([ref.efforts[j] for j in mech.actuated])
        soc_u.append([ours.efforts[j] for j in mech.actuated])
        for joint, reaction in ref.reactions.items():
            determinate &= bool(reaction.determinate[MOMENTS].all())
            moment = ours.reactions[joint][MOMENTS]
            if joint in mech.actuated:
                moment = moment + ours.efforts[joint] * kin.base_axis(mech.params, int(joint[1]))
            pin_m.setdefault(joint, []).append(reaction.wrench[MOMENTS])
            soc_m.setdefault(joint, []).append(moment)

    def rel(x: list, y: list) -> float:
        x, y = np.asarray(x), np.asarray(y)
        return float(np.abs(x - y).max() / np.abs(x).max()) if determinate else float("inf")

    return {
        "efforts": rel(pin_u, soc_u),
        "support": rel(pin_m["hooke_roll"], soc_m["hooke_roll"]),
        "joints": max(rel(pin_m[j], soc_m[j]) for j in pin_m),
        "consistency": consistency,
    }


def self_checks(mech: Mechanism) -> dict[str, float]:
    """`mechkit report` rows: worst errors of the paper's kinematics and of the dynamics.

    Args:
        mech: the platform.

    Returns:
        Check name -> worst error.
    """
    p = mech.params
    trip, normal = cone_round_trip(p, 36)
    dyn = dynamics_agreement(mech, 12)
    return {
        "cone IK -> paper FK round trip (rad)": trip,
        "cone marker point, FK vs plan (-)": normal,
        "J = -B^-1 A vs finite differences (rad/rad)": jacobian_fd_error(p, 6),
        "FK paper vs Newton vs closure solver (rad)": fk_agreement(mech, 6),
        "motor torques Pinocchio vs SOC (rel)": dyn["efforts"],
        "support moment about O Pinocchio vs SOC (rel)": dyn["support"],
        "every joint moment about O Pinocchio vs SOC (rel)": dyn["joints"],
        "SOC consistency residual (rel)": dyn["consistency"],
    }
