"""SOC virtual-work inverse dynamics of the 2-DOF spherical platform (numpy only, no Pinocchio).

Decomposition: one SKC holding the platform, the Hooke cross and both limbs, with the support joint
hooke_roll (strut -> cross) released. Its virtual coordinates (n = 8): the cross's free rotation
about O (3, world), the pitch hooke_pitch, then theta_11, theta_12, theta_21, theta_22; the two
limbs close on the platform at r13, r23 (2 rotation rows each normal to v_i: the internal loop
Jacobian), leaving 4 virtual displacements. Unknowns: the two motor torques and the support moment
about world y and z (4): square. Every body turns about O, so the forces at O do no virtual work:
they are the statically indeterminate part of every reaction (the loops carry any self-balanced
force through O), and the support moment about X0 is zero (the roll axis is free).

Bodies, inertias and motion come from the parameters and the paper's kinematics
(`spherical_2dof_kinematics`): the inertias are re-derived here from the same sizes as the xacro.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from mechkit.mechanisms import spherical_2dof_kinematics as kin
from mechkit.validation.soc import BodyLoad, SKCInstant, SOCResult, WrenchSite, solve_soc

__all__ = ["body_inertias", "skc", "solve"]

N = 8
_CROSS, _PITCH, _THETA = slice(0, 3), 3, {(1, 1): 4, (1, 2): 5, (2, 1): 6, (2, 2): 7}


def _skew(c: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -c[2], c[1]], [c[2], 0.0, -c[0]], [-c[1], c[0], 0.0]])


def body_inertias(p: kin.Geometry) -> dict[str, tuple[float, np.ndarray, np.ndarray]]:
    """Mass (kg), COM (m) and inertia about the COM (kg m^2), both in the body's joint frame.

    Limb links: a bar of square section ``link_width`` along the chord between the points where
    its two axes pierce the sphere of radius ``radius`` (as in the xacro). Platform: a disc at
    ``platform_height`` on its normal. Cross: a cube at O.
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
            inertia = turn @ np.diag([transverse, axial, transverse]) @ turn.T
            out[f"link{i}{j}"] = (m, com, inertia)
    mp, rp, tp = p.platform_mass, p.platform_radius, p.platform_thickness
    side = mp * (3 * rp**2 + tp**2) / 12
    out["platform"] = (mp, np.array([0.0, 0.0, p.platform_height]), np.diag([side, side, mp * rp**2 / 2]))
    mc = p.cross_mass
    out["cross"] = (mc, np.zeros(3), np.eye(3) * mc * p.cross_size**2 / 6)
    return out


def _body(name: str, props: tuple[float, np.ndarray, np.ndarray], rot: np.ndarray, omega: np.ndarray,
          alpha: np.ndarray, jw: np.ndarray) -> BodyLoad:
    """A body turning about O with world rotation ``rot`` and virtual rotation columns ``jw``."""
    m, com_local, inertia_local = props
    c = rot @ com_local
    acc = np.cross(alpha, c) + np.cross(omega, np.cross(omega, c))
    return BodyLoad(name, m, rot @ inertia_local @ rot.T, acc, omega, alpha, -_skew(c) @ jw, jw)


def skc(p: kin.Geometry, phi: Sequence[float], phi_d: Sequence[float], phi_dd: Sequence[float],
        branches: Sequence[int] = (1, 1)) -> SKCInstant:
    """The single SKC (support released) at one instant of a platform motion (rad, rad/s, rad/s^2)."""
    props = body_inertias(p)
    theta = kin.inverse_kinematics(p, phi, branches)
    omega_p, alpha_p = kin.hooke_rates(phi, phi_d, phi_dd)
    jw_cross = np.zeros((3, N))
    jw_cross[:, _CROSS] = np.eye(3)
    jw_platform = jw_cross.copy()
    jw_platform[:, _PITCH] = kin.rot_x(phi[0])[:, 1]
    ex = np.array([1.0, 0.0, 0.0])
    bodies = [
        _body("cross", props["cross"], kin.rot_x(phi[0]), phi_d[0] * ex, phi_dd[0] * ex, jw_cross),
        _body("platform", props["platform"], kin.platform_rotation(phi), omega_p, alpha_p, jw_platform),
    ]
    loop_rows = []
    actuators = []
    for k, i in enumerate((1, 2)):
        u, w, v = kin.base_axis(p, i), kin.middle_axis(p, i, theta[k]), kin.platform_axis(p, i, phi)
        rate, acc = kin.limb_rates(p, i, theta[k], phi, omega_p, alpha_p)
        frame1 = kin.base_frame(p, i) @ kin.rot_z(theta[k])
        frame2 = frame1 @ kin.rot_x(-p.alpha1) @ kin.rot_z(kin.limb_angles(p, i, theta[k], phi)[0])
        jw1, jw2 = np.zeros((3, N)), np.zeros((3, N))
        jw1[:, _THETA[i, 1]] = jw2[:, _THETA[i, 1]] = u
        jw2[:, _THETA[i, 2]] = w
        w1 = rate[0] * u
        bodies.append(_body(f"link{i}1", props[f"link{i}1"], frame1, w1, acc[0] * u, jw1))
        bodies.append(_body(f"link{i}2", props[f"link{i}2"], frame2, w1 + rate[1] * w,
                            acc[0] * u + acc[1] * w + np.cross(w1, rate[1] * w), jw2))
        # r{i}3 closed: platform and link i2 turn alike except about v_i.
        normal = np.linalg.svd(v.reshape(1, 3))[2][1:]
        loop_rows.append(normal @ (jw_platform - jw2))
        direction = np.zeros(N)
        direction[_THETA[i, 1]] = 1.0
        actuators.append((f"r{i}1", direction))
    support = WrenchSite("hooke_roll", np.vstack([np.zeros((3, N)), jw_cross]), sign=1.0, components=(4, 5))
    return SKCInstant("platform+limbs (support released)", N, bodies, actuators, released=(support,),
                      loop_jacobian=np.vstack(loop_rows))


def solve(p: kin.Geometry, phi: Sequence[float], phi_d: Sequence[float], phi_dd: Sequence[float],
          branches: Sequence[int] = (1, 1), gravity: np.ndarray = np.array([0.0, 0.0, -9.81])) -> SOCResult:
    """Motor torques r11, r21 (N m) and the support moment at hooke_roll (strut on cross, world, at O)."""
    return solve_soc([skc(p, phi, phi_d, phi_dd, branches)], gravity)
