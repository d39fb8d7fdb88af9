"""The 2T1R's inverse dynamics without Pinocchio: SKC decomposition for `mechkit.validation.soc`
and the classic whole-mechanism virtual work (eqs. (39)-(40)), numpy only.

Motion from the paper's analytic kinematics (`kinematics`, `rates`); virtual-displacement
Jacobians from the joint points (a planar revolute chain about +y: dP/dq_j = e_y x (P - J_j)).
SKCs in the paper's order (section 4.3):

- SKC3, limb III (A4-B4-C4), coordinates (q41, q42): R43 released, its in-plane force unknown.
- SKC2, limb II + platform (A3-B3-C3-p), coordinates (q31, q32, q33): R23 released, motor M3,
  R43 known.
- SKC1, limb I five-bar (A1-B1-C1-B2-A2), coordinates (q11, q12, q21, q22) with the loop at C1
  (R13) as internal closure: motors M1, M2, R23 known.

Reactions are parent on child, world frame, at the joint point (R23: link22 on the platform; R43:
link42 on the platform), as in the URDF. Only fx and fz are unknowns of a released pin: with every
axis along y the out-of-plane force and the in-plane moments are statically indeterminate (the
planar model sets them to zero) and my is zero for an unactuated pin.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import SingularConfiguration
from mechkit.base.spatial import cross, rot_y
from mechkit.mechanisms.parallel_2t1r import kinematics as kin
from mechkit.mechanisms.parallel_2t1r import rates
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams, mass_properties
from mechkit.validation.soc import RANK_TOL, BodyLoad, SKCInstant, SOCResult, WrenchSite, solve_soc

__all__ = ["GRAVITY", "Points", "classic_torques", "skcs", "soc_inverse_dynamics"]

GRAVITY = np.array([0.0, 0.0, -9.81])
PIN = (0, 2)  # unknown world components of a released pin: fx, fz


@dataclass(frozen=True)
class Points:
    """Joint points (3,) m of one instant: A, B, C per limb (index 0..3), platform centroid p."""

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    p: np.ndarray

    @classmethod
    def of(cls, d: kin.Dims, s: rates.State) -> Points:
        """The points (world, m) of a motion state at dimensions d.

        Args:
            d: the mechanism's dimensions (m).
            s: a motion state.

        Returns:
            The points.
        """
        return cls(
            kin.base_points(d),
            kin.elbow_points(d, s.theta),
            kin.end_points(d, s.pose),
            kin.platform_points(d, s.pose)["p"],
        )


def _point_jacobian(point: np.ndarray, pivots: list[np.ndarray | None]) -> np.ndarray:
    """(3, n) dP/dq for a planar chain of revolutes about +y; None marks a coordinate not upstream."""
    return np.column_stack([np.zeros(3) if j is None else cross(kin.EY, point - j) for j in pivots])


def _site(point: np.ndarray, pivots: list[np.ndarray | None]) -> np.ndarray:
    """(6, n) site Jacobian: the point's displacement and the rotation of the body carrying it."""
    rot = np.column_stack([np.zeros(3) if j is None else kin.EY for j in pivots])
    return np.vstack([_point_jacobian(point, pivots), rot])


def _loads(p: Parallel2T1RParams, s: rates.State) -> dict[str, tuple[float, np.ndarray, rates.BodyMotion]]:
    """Per body: mass, world inertia about the COM, motion (eqs. (16)-(29))."""
    motion = rates.link_motion(p.dims, s)
    out = {}
    for name, (mass, _, inertia) in mass_properties(p).items():
        r = rot_y(motion[name].angle)
        out[name] = (mass, r @ inertia @ r.T, motion[name])
    return out


def skcs(p: Parallel2T1RParams, s: rates.State, m4: float | None = None) -> list[SKCInstant]:
    """SKC3, SKC2, SKC1 at one instant (see the module docstring).

    Args:
        p: the parameters.
        s: a motion state.
        m4: effort (N m) of the R41 motor in the redundantly actuated variant, known beforehand (e.g. from
            `classic_torques`' minimum-norm distribution); None for a passive limb III.

    Returns:
        The SKCs in solve order.
    """
    pts = Points.of(p.dims, s)
    loads = _loads(p, s)
    a, b, c = pts.a, pts.b, pts.c

    def body(name: str, pivots: list[np.ndarray | None]) -> BodyLoad:
        mass, inertia, m = loads[name]
        site = _site(m.com, pivots)
        return BodyLoad(name, mass, inertia, m.a_com, m.omega, m.alpha, site[:3], site[3:])

    ext3 = () if m4 is None else ((np.array([0, 0, 0, 0, m4, 0.0]), _site(a[3], [a[3], None])),)
    skc3 = SKCInstant(
        "SKC3",
        2,
        [body("link41", [a[3], None]), body("link42", [a[3], b[3]])],
        released=[WrenchSite("R43", _site(c[3], [a[3], b[3]]), -1.0, PIN)],
        external=ext3,
    )
    chain2 = [a[2], b[2], c[2]]
    skc2 = SKCInstant(
        "SKC2",
        3,
        [body("link31", [a[2], None, None]), body("link32", [a[2], b[2], None]), body("platform", chain2)],
        actuators=[("R31", np.array([1.0, 0.0, 0.0]))],
        released=[WrenchSite("R23", _site(c[0], chain2), 1.0, PIN)],
        known=[WrenchSite("R43", _site(c[3], chain2), 1.0)],
    )
    tip1 = _point_jacobian(c[0], [a[0], b[0], None, None])
    tip2 = _point_jacobian(c[0], [None, None, a[1], b[1]])
    skc1 = SKCInstant(
        "SKC1",
        4,
        [
            body("link11", [a[0], None, None, None]),
            body("link12", [a[0], b[0], None, None]),
            body("link21", [None, None, a[1], None]),
            body("link22", [None, None, a[1], b[1]]),
        ],
        actuators=[("R11", np.array([1.0, 0, 0, 0])), ("R21", np.array([0, 0, 1.0, 0]))],
        known=[WrenchSite("R23", _site(c[0], [None, None, a[1], b[1]]), -1.0)],
        loop_jacobian=(tip1 - tip2)[PIN, :],
    )
    return [skc3, skc2, skc1]


def soc_inverse_dynamics(p: Parallel2T1RParams, s: rates.State, m4: float | None = None) -> SOCResult:
    """Efforts M1..M3 and the reactions at R43 and R23 by the SOC method (`mechkit.validation.soc`).

    Args:
        p: the parameters.
        s: a motion state.
        m4: R41's motor torque (N m), as in `skcs`.

    Returns:
        Efforts (N m) and the reactions at R23 and R43 (world wrenches (6,)).

    Raises:
        SingularConfiguration: an SKC's virtual-work system is singular (e.g. SKC2 when limb II's
            distal link points at the platform centre, SKC1 at a five-bar singularity).
    """
    return solve_soc(skcs(p, s, m4), GRAVITY)


def _whole_jacobians(p: Parallel2T1RParams, s: rates.State) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Body site Jacobians (6, 3) over the platform pose X = (x_p, z_p, alpha), and d theta / dX (4, 3).

    Obtained from the velocity equations (11), (16)-(29) with unit platform rates: the body
    velocities are linear in the rates, so each column is one evaluation with X' = e_k.
    """
    d = p.dims
    jp, jq = rates.jacobians(d, s.theta, s.pose)
    g = np.diag(jq)
    if np.min(np.abs(g)) < RANK_TOL * np.max(np.abs(g)):
        raise SingularConfiguration(np.inf, "J_q: a limb is stretched or folded (serial singularity)")
    cols: dict[str, list[np.ndarray]] = {}
    dtheta = np.zeros((4, 3))
    for k in range(3):
        x_dot = np.eye(3)[k]
        td = jp @ x_dot / g
        t4d = rates.follower_rate(d, s.theta, s.pose, x_dot)
        dtheta[:, k] = np.append(td, t4d)
        unit = rates.State(s.pose, x_dot, np.zeros(3), s.theta, dtheta[:, k], np.zeros(4))
        for name, m in rates.link_motion(d, unit).items():
            cols.setdefault(name, []).append(np.concatenate([m.v_com, m.omega]))
    return {name: np.column_stack(c) for name, c in cols.items()}, dtheta


def classic_torques(
    p: Parallel2T1RParams, s: rates.State, actuated: tuple[str, ...] = ("R11", "R21", "R31"), max_cond: float = 1e10
) -> tuple[dict[str, float], float]:
    """Driving torques by the classic whole-mechanism virtual work, eqs. (39)-(40).

    With the platform pose X as generalised coordinates: sum_bodies J_v^T F + J_w^T M + J_a^T u = 0,
    J_a = d theta_actuated / dX. For the paper's three motors J_a = J_q^-1 J_p and this is eq. (40)
    (u = -J_q^T J_p^-T Q_X, the chain rule of its Jacobians over theta). With four motors
    (``R41`` added) the system has a one-dimensional family of solutions; the minimum-norm torques
    (pseudo-inverse) are returned.

    Args:
        p: the parameters.
        s: a motion state.
        actuated: the motors.
        max_cond: the largest condition number of J_a accepted.

    Returns:
        (efforts by joint name (N m), condition number of J_a).

    Raises:
        SingularConfiguration: J_a loses rank (cond > max_cond): the motors cannot hold the platform.
    """
    jac, dtheta = _whole_jacobians(p, s)
    q_x = np.zeros(3)
    for name, (mass, inertia, m) in _loads(p, s).items():
        force = mass * (GRAVITY - m.a_com)
        moment = -inertia @ m.alpha - cross(m.omega, inertia @ m.omega)
        q_x += jac[name][:3].T @ force + jac[name][3:].T @ moment
    rows = [int(j[1]) - 1 for j in actuated]
    ja = dtheta[rows]
    sv = np.linalg.svd(ja, compute_uv=False)
    cond = float(sv[0] / sv[-1]) if sv[-1] > 0 else np.inf
    if len(sv) < 3 or cond > max_cond:
        raise SingularConfiguration(cond, f"classic virtual work: d theta/dX of {actuated}")
    u = np.linalg.lstsq(ja.T, -q_x, rcond=None)[0]
    return dict(zip(actuated, map(float, u))), cond
