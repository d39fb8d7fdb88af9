"""2-DOF spherical parallel platform for low-frequency vibration isolation (Zhang et al. 2016).

A platform on a central strut through a Hooke joint at O, driven by two RRR limbs whose axes all
pass through O (every point moves on a sphere about O). Motors at the base joints r11, r21.
The paper's own kinematics (eqs. 4-12, the iterative forward kinematics) live in
`spherical_2dof_kinematics`; the SOC decomposition in `spherical_2dof_soc`. Conventions the source
leaves out (roll/pitch, platform-side axes, the reading of "cone angle 30 deg") are derived in
docs/mechanisms/spherical_2dof.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from mechkit.exceptions import InvalidParameters
from mechkit.mechanisms import spherical_2dof_kinematics as kin
from mechkit.params import MechanismParams, param
from mechkit.contract import MechanismSpec

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

#: Cone scene: the paper's "cone angle 30 deg" (錐角) read as the apex angle: half angle 15 deg.
CONE_HALF_ANGLE = math.radians(15.0)
#: Cone scene: one turn of the normal about Z0 in 2 s (ours: "constant speed" is all the paper says).
CONE_PERIOD = 2.0
#: Assembly branch (+1 / -1 per limb, see `kin.inverse_kinematics`) used for every scene (ours).
BRANCHES = (1, 1)


@dataclass(frozen=True)
class Spherical2DofParams(MechanismParams):
    alpha1: float = param(math.radians(25.0), "rad", "arc between the motor axis u_i and the middle axis w_i")
    alpha2: float = param(
        math.radians(30.0), "rad", "arc between the middle axis w_i and the platform axis v_i"
    )
    beta: float = param(math.radians(53.13), "rad", "angle of the motor axes u_i from -Z0 (eq. 5)")
    beta_platform: float = param(
        math.radians(90.0),
        "rad",
        "angle of the platform axes v_i from -Z (absent from the paper; 90 deg: in the platform plane)",
        ours=True,
    )
    eta11: float = param(
        0.0, "rad", "base azimuth of limb 1's motor axis u_1 (the reference: 0 by definition of X0)"
    )
    eta12: float = param(math.radians(90.0), "rad", "base azimuth of limb 2's motor axis u_2 from u_1")
    eta21: float = param(
        0.0, "rad", "platform azimuth of limb 1's platform axis v_1 (the reference: 0 by definition of X)"
    )
    eta22: float = param(math.radians(90.0), "rad", "platform azimuth of limb 2's platform axis v_2 from v_1")
    radius: float = param(0.12, "m", "sphere radius of the limb links (joint points)", ours=True)
    link_width: float = param(0.02, "m", "square section side of the limb links", ours=True)
    density: float = param(2700.0, "kg/m^3", "aluminium limb links", ours=True)
    platform_mass: float = param(2.0, "kg", "platform with its isolated payload", ours=True)
    platform_radius: float = param(0.15, "m", "platform disc radius", ours=True)
    platform_thickness: float = param(0.01, "m", "platform disc thickness", ours=True)
    platform_height: float = param(0.05, "m", "platform centre of mass above O along its normal", ours=True)
    cross_mass: float = param(0.1, "kg", "Hooke-joint cross (a cube at O)", ours=True)
    cross_size: float = param(0.03, "m", "Hooke-joint cross cube side", ours=True)
    rows: str = param(
        "spherical",
        "-",
        "closure rows per cut: spherical (2 rotation rows) or spatial (5, 3 of them redundant)",
    )

    def validate(self) -> None:
        if self.rows not in ("spherical", "spatial"):
            raise InvalidParameters("rows", self.rows, "one of 'spherical', 'spatial'")
        for name in ("alpha1", "alpha2"):
            if not 0.0 < getattr(self, name) < math.pi / 2:
                raise InvalidParameters(name, getattr(self, name), "a link arc must lie in (0, 90) deg")
        lo, hi = abs(self.alpha1 - self.alpha2), self.alpha1 + self.alpha2
        for i in (1, 2):
            arc = math.acos(
                float(np.clip(kin.base_axis(self, i) @ kin.platform_axis(self, i, (0.0, 0.0)), -1, 1))
            )
            if not lo < arc < hi:
                why = (
                    f"limb {i} cannot assemble at home: the u-v arc {math.degrees(arc):.2f} deg is outside "
                    f"(|alpha1 - alpha2|, alpha1 + alpha2) = ({math.degrees(lo):.2f}, {math.degrees(hi):.2f}) deg"
                )
                raise InvalidParameters("beta_platform", self.beta_platform, why)


def tree_configuration(p: Spherical2DofParams, phi: np.ndarray, theta: np.ndarray) -> dict[str, float]:
    """Every tree joint (rad) at attitude ``phi`` and motor angles ``theta`` (closed with eq. 7)."""
    joints = {"hooke_roll": float(phi[0]), "hooke_pitch": float(phi[1])}
    for k, i in enumerate((1, 2)):
        joints[f"r{i}1"] = float(theta[k])
        joints[f"r{i}2"] = kin.limb_angles(p, i, theta[k], phi)[0]
    return joints


def _home(p: Spherical2DofParams) -> dict[str, float]:
    theta = kin.inverse_kinematics(p, (0.0, 0.0), BRANCHES)
    return {"r11": float(theta[0]), "r21": float(theta[1])}


def _guess(p: Spherical2DofParams) -> dict[str, float]:
    return tree_configuration(p, np.zeros(2), kin.inverse_kinematics(p, (0.0, 0.0), BRANCHES))


def cone_attitude(
    t: np.ndarray | float, half_angle: float = CONE_HALF_ANGLE, period: float = CONE_PERIOD
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cone scene: the platform normal n = [s(g) c(psi), s(g) s(psi), c(g)], psi = 2 pi t / period.

    With n = Rx(phi_x) Ry(phi_y) e_z: phi_y = asin(s(g) c(psi)), phi_x = atan(-tan(g) s(psi)).

    Args:
        t: time(s), s.
        half_angle: g, the cone's half angle (rad).
        period: one turn, s.

    Returns:
        phi, phi', phi'' as arrays (..., 2) (rad, rad/s, rad/s^2), columns (roll, pitch).
    """
    if not 0.0 <= half_angle < math.pi / 2:
        raise InvalidParameters("half_angle", half_angle, "must lie in [0, 90) deg")
    if not period > 0.0:
        raise InvalidParameters("period", period, "must be > 0 s")
    w = 2.0 * math.pi / period
    psi = w * np.asarray(t, dtype=float)
    sg, tg = math.sin(half_angle), math.tan(half_angle)
    g, g1, g2 = sg * np.cos(psi), -sg * w * np.sin(psi), -sg * w**2 * np.cos(psi)
    root = np.sqrt(1.0 - g**2)
    h, h1, h2 = -tg * np.sin(psi), -tg * w * np.cos(psi), tg * w**2 * np.sin(psi)
    den = 1.0 + h**2
    phi = np.stack([np.arctan(h), np.arcsin(g)], axis=-1)
    phi_d = np.stack([h1 / den, g1 / root], axis=-1)
    phi_dd = np.stack([h2 / den - 2.0 * h * h1**2 / den**2, g2 / root + g * g1**2 / root**3], axis=-1)
    return phi, phi_d, phi_dd


def platform_normal(phi: np.ndarray) -> np.ndarray:
    """Unit platform normal n = R(phi) e_z (base frame) of attitudes (..., 2)."""
    phi = np.asarray(phi, dtype=float)
    px, py = phi[..., 0], phi[..., 1]
    return np.stack([np.sin(py), -np.sin(px) * np.cos(py), np.cos(px) * np.cos(py)], axis=-1)


def state(
    mech: Mechanism,
    phi: np.ndarray,
    phi_d: np.ndarray,
    phi_dd: np.ndarray,
    branches: tuple[int, int] = BRANCHES,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pinocchio (q, v, a) of a platform motion, from the paper's kinematics alone (no closure solve).

    Motor angles by eq. (8); joint rates and accelerations by the limb velocity loops
    (`kin.limb_rates`).
    """
    p = mech.params
    theta = kin.inverse_kinematics(p, phi, branches)
    q, v, a = mech.neutral(), np.zeros(mech.model.nv), np.zeros(mech.model.nv)
    for joint, value in tree_configuration(p, phi, theta).items():
        q[mech.q_index(joint)] = value
    omega, alpha = kin.hooke_rates(phi, phi_d, phi_dd)
    for j, joint in enumerate(("hooke_roll", "hooke_pitch")):
        v[mech.v_index(joint)], a[mech.v_index(joint)] = phi_d[j], phi_dd[j]
    for k, i in enumerate((1, 2)):
        rate, acc = kin.limb_rates(p, i, theta[k], phi, omega, alpha)
        for j in range(2):
            v[mech.v_index(f"r{i}{j + 1}")], a[mech.v_index(f"r{i}{j + 1}")] = rate[j], acc[j]
    return q, v, a


def _cone_scene(mech: Mechanism) -> list[np.ndarray]:
    """One turn of the cone scene as assembled configurations (for animated snapshots)."""
    phi, phi_d, phi_dd = cone_attitude(np.linspace(0.0, CONE_PERIOD, 73))
    return [state(mech, *x)[0] for x in zip(phi, phi_d, phi_dd, strict=True)]


#: Animated scenes for `mechkit snapshot spherical_2dof --scene cone`.
SCENES = {"cone": _cone_scene}


def _bench_fk(method: str):
    """`mechkit bench` assembly method: FK (``kin.fk_paper`` or ``kin.fk_newton``) from home, then the tree."""
    solve = kin.fk_paper if method == "paper" else kin.fk_newton

    def run(mech: Mechanism, sample) -> np.ndarray:
        phi = solve(mech.params, sample.inputs, np.zeros(2)).phi
        q = mech.neutral()
        for joint, value in tree_configuration(mech.params, phi, sample.inputs).items():
            q[mech.q_index(joint)] = value
        return q

    return run


def _bench_soc(mech: Mechanism, sample):
    """SOC virtual work (numpy), every joint's moment about O."""
    from mechkit.mechanisms.spherical_2dof_soc import solve

    hooke = [mech.v_index("hooke_roll"), mech.v_index("hooke_pitch")]
    phi = [sample.q[mech.q_index("hooke_roll")], sample.q[mech.q_index("hooke_pitch")]]
    return solve(mech.params, phi, sample.v[hooke], sample.a[hooke], BRANCHES)


#: `mechkit bench` methods (protocol in `mechkit.bench`); the SOC is also the independent reference.
BENCH_METHODS = {
    "assembly": [
        ("paper FK (Newton on IK eq. 8)", _bench_fk("paper")),
        ("Newton FK on eq. (7)", _bench_fk("newton")),
    ],
    "inverse_dynamics": [("SOC (numpy)", _bench_soc)],
}
BENCH_REFERENCE = {"inverse_dynamics": _bench_soc}


def _self_checks(mech: Mechanism) -> dict[str, float]:
    from mechkit.mechanisms.spherical_2dof_checks import self_checks

    return self_checks(mech)


SPEC = MechanismSpec(
    name="spherical_2dof",
    params=Spherical2DofParams,
    template="spherical_2dof.urdf.xacro",
    actuated=("r11", "r21"),
    gruebler_dof=2,
    home=_home,
    guess=_guess,
    summary="2-DOF spherical parallel platform (2 RRR limbs + central Hooke strut), vibration isolation",
    self_checks=_self_checks,
)
