"""SOC virtual-work inverse dynamics of the 2-DOF spherical platform (numpy only, no Pinocchio).

Every body turns about O, so the forces at O do no virtual work: they are the statically
indeterminate part of every reaction (the two loops carry any self-balanced force through O), and
only the moments about O are solved. The SKCs, in order (virtual coordinates in brackets):

1. ``mechanism``: platform, cross and both limbs with the support hooke_roll released
   [cross rotation about O (3), hooke_pitch, theta_11, theta_12, theta_21, theta_22]; the limbs close
   on the platform at r13, r23 (2 rotation rows each, normal to v_i: the internal loop Jacobian),
   leaving 4 virtual displacements for 4 unknowns: the motor torques r11, r21 and the support
   moment about world y and z (the roll axis X0 is free). The two loops share the platform, so the
   efforts need this whole-mechanism SKC.
2. ``cross`` [its rotation (3)]: hooke_roll known, hooke_pitch released (2 moments normal to the
   pitch axis): one equation to spare, reported as the consistency residual.
3. ``limb i`` [rotation of link i1 (3), theta_i2]: the motor torque applied as known, r{i}1 (2
   moments normal to u_i) and r{i}3 (2 normal to v_i) released: square.
4. ``link i2`` [its rotation (3)]: r{i}3 known, r{i}2 released (2 normal to w_i): one to spare.

Reactions: parent on child, world, at O; the motor joints' reactions exclude the motor torque
(add ``effort * u_i`` for the wrench the joint transmits). Bodies, inertias and motion come from
the parameters and the paper's kinematics (`spherical_2dof.kinematics`); the inertias are
re-derived here from the same sizes as the xacro.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from mechkit.base.spatial import skew
from mechkit.mechanisms.spherical_2dof import kinematics as kin
from mechkit.validation.soc import BodyLoad, SKCInstant, SOCResult, WrenchSite, solve_soc

__all__ = ["BodyMotion", "body_inertias", "body_motions", "skcs", "solve"]


def body_inertias(p: kin.Geometry) -> dict[str, tuple[float, np.ndarray, np.ndarray]]:
    """Mass (kg), COM (m) and inertia about the COM (kg m^2), both in the body's joint frame.

    Limb links: a bar of square section ``link_width`` along the chord between the points where
    its two axes pierce the sphere of radius ``radius`` (as in the xacro). Platform: a disc at
    ``platform_height`` on its normal. Cross: a cube at O.

    Args:
        p: the structural parameters.

    Returns:
        Body -> (mass, COM (3,), inertia (3, 3)).
    """
    out = {}
    w = p.link_width
    for i in (1, 2):
        for j, alpha in ((1, p.alpha1), (2, p.alpha2)):
            length = 2.0 * p.radius * np.sin(alpha / 2)
            m = p.density * length * w * w
            turn = kin.rot_x(-alpha / 2)
            com = p.radius * np.cos(alpha / 2) * turn[:, 2]
            axial, transverse = m * w * w / 6, m * (length**2 + w * w) / 12
            out[f"link{i}{j}"] = (m, com, turn @ np.diag([transverse, axial, transverse]) @ turn.T)
    mp, rp, tp = p.platform_mass, p.platform_radius, p.platform_thickness
    side = mp * (3 * rp**2 + tp**2) / 12
    out["platform"] = (mp, np.array([0.0, 0.0, p.platform_height]), np.diag([side, side, mp * rp**2 / 2]))
    mc = p.cross_mass
    out["cross"] = (mc, np.zeros(3), np.eye(3) * mc * p.cross_size**2 / 6)
    return out


@dataclass(frozen=True)
class BodyMotion:
    """A body turning about O at one instant (world): mass (kg), inertia about the COM (kg m^2),
    COM (m), angular velocity (rad/s) and acceleration (rad/s^2)."""

    mass: float
    inertia: np.ndarray
    com: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray

    def load(self, name: str, jw: np.ndarray) -> BodyLoad:
        """The body in an SKC whose virtual rotation of this body is ``jw`` (3, n).

        Args:
            name: the body's name.
            jw: the SKC's virtual rotation of the body (3, n).

        Returns:
            The body for the SOC solver.
        """
        c = self.com
        acc = kin.cross(self.alpha, c) + kin.cross(self.omega, kin.cross(self.omega, c))
        return BodyLoad(name, self.mass, self.inertia, acc, self.omega, self.alpha, -skew(c) @ jw, jw)


def _motion(
    props: tuple[float, np.ndarray, np.ndarray], rot: np.ndarray, omega: np.ndarray, alpha: np.ndarray
) -> BodyMotion:
    m, com, inertia = props
    return BodyMotion(m, rot @ inertia @ rot.T, rot @ com, omega, alpha)


def _moments_normal_to(axis: np.ndarray) -> np.ndarray:
    """(6, 2) wrench basis: pure moments along two unit directions normal to ``axis``."""
    basis = np.zeros((6, 2))
    basis[3:] = np.linalg.svd(axis.reshape(1, 3))[2][1:].T
    return basis


def _site(joint: str, jw: np.ndarray, sign: float, axis: np.ndarray | None = None) -> WrenchSite:
    """A joint at O on a body of virtual rotation ``jw``; released along moments normal to ``axis``."""
    jacobian = np.vstack([np.zeros_like(jw), jw])
    return WrenchSite(joint, jacobian, sign, basis=None if axis is None else _moments_normal_to(axis))


def _columns(n: int, cols: dict[int, np.ndarray]) -> np.ndarray:
    """(3, n) matrix with the given columns, zeros elsewhere."""
    out = np.zeros((3, n))
    for j, col in cols.items():
        out[:, j] = col
    return out


def _bodies(
    p: kin.Geometry,
    phi: Sequence[float],
    phi_d: Sequence[float],
    phi_dd: Sequence[float],
    branches: Sequence[int],
) -> tuple[dict[str, BodyMotion], dict[int, tuple[np.ndarray, ...]]]:
    """Every body's motion, and per limb its axes (u_i, w_i, v_i), from the paper's kinematics."""
    props = body_inertias(p)
    theta = kin.inverse_kinematics(p, phi, branches)
    omega_p, alpha_p = kin.hooke_rates(phi, phi_d, phi_dd)
    ex = np.eye(3)[0]
    body = {
        "cross": _motion(props["cross"], kin.rot_x(phi[0]), phi_d[0] * ex, phi_dd[0] * ex),
        "platform": _motion(props["platform"], kin.platform_rotation(phi), omega_p, alpha_p),
    }
    axes = {}
    for k, i in enumerate((1, 2)):
        u, w, v = kin.base_axis(p, i), kin.middle_axis(p, i, theta[k]), kin.platform_axis(p, i, phi)
        axes[i] = (u, w, v)
        rate, acc = kin.limb_rates(p, i, theta[k], phi, omega_p, alpha_p)
        frame1 = kin.base_frame(p, i) @ kin.rot_z(theta[k])
        frame2 = frame1 @ kin.rot_x(-p.alpha1) @ kin.rot_z(kin.limb_angles(p, i, theta[k], phi)[0])
        w1 = rate[0] * u
        body[f"link{i}1"] = _motion(props[f"link{i}1"], frame1, w1, acc[0] * u)
        body[f"link{i}2"] = _motion(
            props[f"link{i}2"], frame2, w1 + rate[1] * w, acc[0] * u + acc[1] * w + kin.cross(w1, rate[1] * w)
        )
    return body, axes


def body_motions(
    p: kin.Geometry,
    phi: Sequence[float],
    phi_d: Sequence[float],
    phi_dd: Sequence[float],
    branches: Sequence[int] = kin.BRANCHES,
) -> dict[str, BodyMotion]:
    """Motion of every moving body (cross, platform, link11, link12, link21, link22) at one instant.

    Args:
        p: the structural parameters.
        phi: attitude (roll, pitch), rad.
        phi_d: its rates, rad/s.
        phi_dd: its accelerations, rad/s^2.
        branches: the IK branch per limb.

    Returns:
        Body -> its motion (world).
    """
    return _bodies(p, phi, phi_d, phi_dd, branches)[0]


def skcs(
    p: kin.Geometry,
    phi: Sequence[float],
    phi_d: Sequence[float],
    phi_dd: Sequence[float],
    efforts: dict[str, float] | None = None,
    branches: Sequence[int] = kin.BRANCHES,
) -> list[SKCInstant]:
    """The SKCs at one instant of a platform motion (rad, rad/s, rad/s^2), in solving order.

    Args:
        p: the structural parameters.
        phi: attitude (roll, pitch), rad.
        phi_d: its rates, rad/s.
        phi_dd: its accelerations, rad/s^2.
        efforts: motor torques (N m) solved by the first SKC; without them only the first SKC (which solves them)
            is returned.
        branches: the IK branch per limb.

    Returns:
        The SKCs in solving order.
    """
    body, axes = _bodies(p, phi, phi_d, phi_dd, branches)
    ex, pitch = np.eye(3)[0], kin.rot_x(phi[0])[:, 1]

    # 1. the whole mechanism, support released: [cross (3), pitch, th11, th12, th21, th22]
    n = 8
    jw = {"cross": _columns(n, {0: ex, 1: np.eye(3)[1], 2: np.eye(3)[2]})}
    jw["platform"] = jw["cross"] + _columns(n, {3: pitch})
    loop, actuators = [], []
    for i, first in ((1, 4), (2, 6)):
        u, w, v = axes[i]
        jw[f"link{i}1"] = _columns(n, {first: u})
        jw[f"link{i}2"] = _columns(n, {first: u, first + 1: w})
        loop.append(_moments_normal_to(v)[3:].T @ (jw["platform"] - jw[f"link{i}2"]))
        actuators.append((f"r{i}1", np.eye(n)[first]))
    whole = SKCInstant(
        "mechanism",
        n,
        [body[b].load(b, jw[b]) for b in body],
        actuators,
        released=(WrenchSite("hooke_roll", np.vstack([np.zeros((3, n)), jw["cross"]]), 1.0, components=(4, 5)),),
        loop_jacobian=np.vstack(loop),
    )
    if efforts is None:
        return [whole]

    free = np.eye(3)
    out = [
        whole,
        SKCInstant(
            "cross",
            3,
            [body["cross"].load("cross", free)],
            known=(_site("hooke_roll", free, 1.0),),
            released=(_site("hooke_pitch", free, -1.0, pitch),),
        ),
    ]
    for i in (1, 2):
        u, w, v = axes[i]
        j1, j2 = np.hstack([free, np.zeros((3, 1))]), np.hstack([free, w.reshape(3, 1)])
        torque = np.concatenate([np.zeros(3), efforts[f"r{i}1"] * u])
        out.append(
            SKCInstant(
                f"limb {i}",
                4,
                [body[f"link{i}1"].load(f"link{i}1", j1), body[f"link{i}2"].load(f"link{i}2", j2)],
                released=(_site(f"r{i}1", j1, 1.0, u), _site(f"r{i}3", j2, -1.0, v)),
                external=((torque, np.vstack([np.zeros((3, 4)), j1])),),
            )
        )
        out.append(
            SKCInstant(
                f"link {i}2",
                3,
                [body[f"link{i}2"].load(f"link{i}2", free)],
                known=(_site(f"r{i}3", free, -1.0),),
                released=(_site(f"r{i}2", free, 1.0, w),),
            )
        )
    return out


def solve(
    p: kin.Geometry,
    phi: Sequence[float],
    phi_d: Sequence[float],
    phi_dd: Sequence[float],
    branches: Sequence[int] = kin.BRANCHES,
    gravity: Sequence[float] = (0.0, 0.0, -9.81),
) -> SOCResult:
    """Motor torques r11, r21 (N m) and the moment about O of every joint's reaction (see module doc).

    ``gravity`` (m/s^2, world) defaults to 9.81 along -Z0.

    Args:
        p: the structural parameters.
        phi: attitude (roll, pitch), rad.
        phi_d: its rates, rad/s.
        phi_dd: its accelerations, rad/s^2.
        branches: the IK branch per limb.
        gravity: (3,) m/s^2, world; 9.81 along -Z0 by default.

    Returns:
        Efforts (N m) and every joint's reaction (world wrench (6,)).
    """
    gravity = np.asarray(gravity, dtype=float)
    first = solve_soc(skcs(p, phi, phi_d, phi_dd, None, branches), gravity)
    return solve_soc(skcs(p, phi, phi_d, phi_dd, first.efforts, branches), gravity)
