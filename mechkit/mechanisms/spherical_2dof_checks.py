"""Self-checks of the 2-DOF spherical platform along the cone scene (rows of `mechkit report`).

Each check compares independent methods and returns its worst error (smaller is better).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mechkit.mechanisms import spherical_2dof_kinematics as kin
from mechkit.mechanisms import spherical_2dof_soc as soc
from mechkit.mechanisms.spherical_2dof import BRANCHES, CONE_PERIOD, cone_attitude, platform_normal, state
from mechkit.mechanisms.spherical_2dof_fk import METHODS, solve_fk

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = ["cone_times", "cone_round_trip", "jacobian_fd_error", "fk_agreement", "dynamics_agreement", "self_checks"]

#: Compared components of the support reaction hooke_roll: the moments about world y and z at O
#: (the forces at O are statically indeterminate; the moment about X0 is zero, the roll being free).
SUPPORT_COMPONENTS = (4, 5)


def cone_times(samples: int) -> np.ndarray:
    """``samples`` instants over one turn of the cone scene (s)."""
    return np.linspace(0.0, CONE_PERIOD, samples, endpoint=False)


def cone_round_trip(p: kin.Geometry, samples: int = 72) -> tuple[float, float]:
    """IK of the cone (eq. 8), then the paper's FK of those motor curves, tracking from home.

    Returns:
        (worst attitude error (rad), worst error of the unit normal's tip, the marker point (-)).
    """
    phi_plan = cone_attitude(cone_times(samples))[0]
    phi = np.zeros(2)  # P0: the calibrated home pose
    worst = np.zeros((samples, 2))
    for k, target in enumerate(phi_plan):
        theta = kin.inverse_kinematics(p, target, BRANCHES)
        phi = kin.fk_paper(p, theta, phi, BRANCHES).phi
        worst[k] = phi - target
    normal = np.linalg.norm(platform_normal(phi_plan + worst) - platform_normal(phi_plan), axis=1)
    return float(np.abs(worst).max()), float(normal.max())


def jacobian_fd_error(p: kin.Geometry, samples: int = 12, h: float = 1e-5) -> float:
    """Worst |J - J_fd| (rad/rad): J = -B^-1 A against central differences of the FK (Newton) in theta."""
    worst = 0.0
    for target in cone_attitude(cone_times(samples))[0]:
        theta = kin.inverse_kinematics(p, target, BRANCHES)
        fd = np.column_stack([
            (kin.fk_newton(p, theta + h * e, target).phi - kin.fk_newton(p, theta - h * e, target).phi) / (2 * h)
            for e in np.eye(2)
        ])
        worst = max(worst, float(np.abs(kin.jacobian(p, theta, target) - fd).max()))
    return worst


def fk_agreement(mech: Mechanism, samples: int = 12, offset: float = 0.05) -> float:
    """Worst pairwise difference (rad) of the three FK methods along the cone, started ``offset`` away."""
    worst = 0.0
    for target in cone_attitude(cone_times(samples))[0]:
        theta = kin.inverse_kinematics(mech.params, target, BRANCHES)
        found = [solve_fk(mech, m, theta, target + offset).phi for m in METHODS]
        worst = max(worst, max(float(np.abs(a - b).max()) for a in found for b in found))
    return worst


def dynamics_agreement(mech: Mechanism, samples: int = 24) -> tuple[float, float]:
    """Motor torques and the determinate support moments, Pinocchio vs SOC, along the cone.

    Returns:
        (efforts, support) relative errors: worst |difference| over the scene / the scene's peak
        |value|. The support error is inf if Pinocchio flags a compared component indeterminate
        (the comparison would then be of a convention, not of physics).
    """
    t = cone_times(samples)
    phi, phi_d, phi_dd = cone_attitude(t)
    pin_u, soc_u, pin_m, soc_m = [], [], [], []
    determinate = True
    for k in range(samples):
        q, v, a = state(mech, phi[k], phi_d[k], phi_dd[k])
        ref = mech.inverse_dynamics(q, v, a)
        ours = soc.solve(mech.params, phi[k], phi_d[k], phi_dd[k], BRANCHES)
        pin_u.append([ref.efforts[j] for j in mech.actuated])
        soc_u.append([ours.efforts[j] for j in mech.actuated])
        support = ref.reactions["hooke_roll"]
        determinate &= bool(support.determinate[list(SUPPORT_COMPONENTS)].all())
        pin_m.append(support.wrench[list(SUPPORT_COMPONENTS)])
        soc_m.append(ours.reactions["hooke_roll"][list(SUPPORT_COMPONENTS)])

    def rel(x: list, y: list) -> float:
        x, y = np.asarray(x), np.asarray(y)
        return float(np.abs(x - y).max() / np.abs(x).max())

    return rel(pin_u, soc_u), rel(pin_m, soc_m) if determinate else float("inf")


def self_checks(mech: Mechanism) -> dict[str, float]:
    """`mechkit report` rows: worst errors of the paper's kinematics and of the dynamics."""
    p = mech.params
    trip, normal = cone_round_trip(p, 36)
    efforts, support = dynamics_agreement(mech, 12)
    return {
        "cone IK -> paper FK round trip (rad)": trip,
        "cone marker point, FK vs plan (-)": normal,
        "J = -B^-1 A vs finite differences (rad/rad)": jacobian_fd_error(p, 6),
        "FK paper vs Newton vs closure solver (rad)": fk_agreement(mech, 6),
        "motor torques Pinocchio vs SOC (rel)": efforts,
        "support moment (y, z) Pinocchio vs SOC (rel)": support,
    }
