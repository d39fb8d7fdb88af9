"""The 2-DOF spherical platform's studies, as data (`SPEC.studies`; figures in `figures`, numbers in
docs/mechanisms/spherical_2dof.md).

- `cone`: the cone scene as the paper's Figs. 5-7 show it (motor curves by the IK eq. (8), the
  paper's FK of those curves against the plan, the marker point) plus its dynamics: motor torques
  and the support moment about O, Pinocchio's constrained RNEA against SOC virtual work.
- `basin`: where the forward kinematics fails: for a regular pose of the cone scene and one 0.4 deg
  from the forward singularity, starts on circles of growing radius about the answer, per method,
  with the map of det B over (roll, pitch).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.spherical_2dof import kinematics as kin
from mechkit.mechanisms.spherical_2dof import soc
from mechkit.mechanisms.spherical_2dof.fk import NEAR_SINGULAR, REGULAR, BasinRow, basin_study, fk_paper
from mechkit.mechanisms.spherical_2dof.joint_state import state
from mechkit.mechanisms.spherical_2dof.kinematics import BRANCHES, platform_normal
from mechkit.mechanisms.spherical_2dof.params import Spherical2DofParams
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude, cone_times

#: Start distances (deg) from the answer in the basin study.
RADII_DEG = (0.1, 0.3, 1.0, 2.0, 5.0, 10.0, 20.0, 30.0, 45.0, 60.0)
#: The support moment is read at the Hooke joint on the strut.
SUPPORT = "hooke_roll"


@dataclass(frozen=True)
class Cone:
    """The cone scene, sample by sample (n samples).

    Attributes:
        t: (n,) s.
        actuated: the motor joints.
        phi: (n, 2) planned roll and pitch (rad).
        theta: (n, 2) motor angles by eq. (8) (rad).
        fk: (n, 2) roll and pitch by the paper's FK of `theta` (rad), each from the previous answer.
        efforts: method ("pinocchio", "soc") -> (n, 2) motor torques (N m).
        support: method -> (n, 3) support moment about O (N m, world).
    """

    t: np.ndarray
    actuated: tuple[str, ...]
    phi: np.ndarray
    theta: np.ndarray
    fk: np.ndarray
    efforts: dict[str, np.ndarray]
    support: dict[str, np.ndarray]


def cone(mech: Mechanism, samples: int = 72) -> Cone:
    """The cone scene at `samples` instants over its period: IK, the paper's FK, both dynamics methods.

    Args:
        mech: the platform.
        samples: instants over one turn.

    Returns:
        The study: times, attitudes, motor angles, FK, efforts and support moments by method.
    """
    p = mech.params
    t = cone_times(samples)
    phi, phi_d, phi_dd = cone_attitude(t)
    theta = np.array([kin.inverse_kinematics(p, x, BRANCHES) for x in phi])
    fk = np.zeros_like(phi)
    start = np.zeros(2)  # the calibrated home pose P0
    for k, th in enumerate(theta):
        start = fk[k] = fk_paper(p, th, start, BRANCHES).phi
    efforts, support = {"pinocchio": [], "soc": []}, {"pinocchio": [], "soc": []}
    for k in range(samples):
        q, v, a = state(mech, phi[k], phi_d[k], phi_dd[k])
        ref = mech.inverse_dynamics(q, v, a)
        ours = soc.solve(p, phi[k], phi_d[k], phi_dd[k], BRANCHES)
        efforts["pinocchio"].append([ref.efforts[j] for j in mech.actuated])
        efforts["soc"].append([ours.efforts[j] for j in mech.actuated])
        support["pinocchio"].append(ref.reactions[SUPPORT].wrench[3:])
        support["soc"].append(ours.reactions[SUPPORT][3:])
    return Cone(
        t,
        tuple(mech.actuated),
        phi,
        theta,
        fk,
        {k: np.asarray(x) for k, x in efforts.items()},
        {k: np.asarray(x) for k, x in support.items()},
    )


def cone_summary(c: Cone) -> dict[str, float]:
    """Worst differences (FK vs plan, Pinocchio vs SOC) and the peaks.

    Args:
        c: the cone study.

    Returns:
        Name -> value.
    """
    pin_u, soc_u, pin_m, soc_m = c.efforts["pinocchio"], c.efforts["soc"], c.support["pinocchio"], c.support["soc"]
    return {
        "FK vs plan, attitude (rad)": float(np.abs(c.fk - c.phi).max()),
        "FK vs plan, marker point (-)": float(
            np.linalg.norm(platform_normal(c.fk) - platform_normal(c.phi), axis=1).max()
        ),
        "torques Pinocchio vs SOC (N m)": float(np.abs(pin_u - soc_u).max()),
        "support moment Pinocchio vs SOC (N m)": float(np.abs(pin_m - soc_m).max()),
        "peak |torque| (N m)": float(np.abs(pin_u).max()),
        "peak |support moment| (N m)": float(np.abs(pin_m).max()),
    }


def cone_lines(c: Cone) -> list[str]:
    """`cone_summary` as text lines.

    Args:
        c: the cone study.

    Returns:
        Text lines.
    """
    return [f"{name:40s} {value:.3e}" for name, value in cone_summary(c).items()]


def det_b_map(p: Spherical2DofParams, grid: np.ndarray) -> np.ndarray:
    """det B over a (roll, pitch) grid (rad), (n, n) indexed [roll, pitch]; nan where the IK (eq. 8) has
    no solution.

    Args:
        p: the parameters.
        grid: (n,) angles, rad, on both axes.

    Returns:
        (n, n) det B.
    """
    out = np.full((grid.size, grid.size), np.nan)
    for a, roll in enumerate(grid):
        for b, pitch in enumerate(grid):
            try:
                theta = kin.inverse_kinematics(p, (roll, pitch), BRANCHES)
            except InvalidParameters:
                continue
            out[a, b] = np.linalg.det(kin.constraint_jacobians(p, theta, (roll, pitch))[1])
    return out


@dataclass(frozen=True)
class Basin:
    """The FK's convergence basins.

    Attributes:
        directions: starts per radius.
        poses: pose name -> (2,) target roll and pitch (rad).
        rows: pose name -> one `fk.BasinRow` per method and radius.
        grid: (g,) roll and pitch axis of the det B map (rad).
        det_b: (g, g) det B over it.
    """

    directions: int
    poses: dict[str, np.ndarray]
    rows: dict[str, list[BasinRow]]
    grid: np.ndarray
    det_b: np.ndarray


def basin(mech: Mechanism, directions: int = 24, grid_points: int = 91) -> Basin:
    """`fk.basin_study` at the regular and the near-singular pose for `RADII_DEG`, and the det B map on a
    `grid_points` grid over -30..60 deg.

    Args:
        mech: the platform.
        directions: starts per circle.
        grid_points: points per axis of the det B map.

    Returns:
        The study.
    """
    poses = {"regular": REGULAR, "near singular": NEAR_SINGULAR}
    rows = {name: basin_study(mech, pose, np.radians(RADII_DEG), directions) for name, pose in poses.items()}
    grid = np.radians(np.linspace(-30, 60, grid_points))
    return Basin(directions, poses, rows, grid, det_b_map(mech.params, grid))


def basin_lines(b: Basin) -> list[str]:
    """The basin table: per pose, method and radius, the fractions found / elsewhere / failed and iterations.

    Args:
        b: the basin study.

    Returns:
        Text lines.
    """
    out = [f"{'pose':14s} {'method':8s} {'r (deg)':>8s} {'found':>6s} {'other':>6s} {'failed':>6s} {'iters':>6s}"]
    for name, rows in b.rows.items():
        out += [
            f"{name:14s} {r.method:8s} {np.degrees(r.radius):8.1f} {r.found:6.2f} {r.elsewhere:6.2f} "
            f"{r.failed:6.2f} {r.iterations:6.2f}"
            for r in rows
        ]
    return out
