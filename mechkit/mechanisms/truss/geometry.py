"""The paper's analytic geometry of the 3RR-3URU unit and the 9RR-12URU composite (numpy only).

Xu et al., Journal of Deep Space Exploration 4(4) 2017 (references/003), eq. (6)-(13); the drive
laws of section 3.2 are in `mechkit.mechanisms.truss.drives`. Frames: A-xyz at the fixed node A,
z up; O1-x1y1z1 at the circumcentre O1 of triangle ABE, z1 along O1H, x1 along O1A. Units SI and
radians.

Stated reading of what the text leaves open (see docs/mechanisms/deployable_9rr12uru.md; the sign
of gamma is read in `truss.drives`):

- Node orientation (eq. 9). Each outer node turns relative to O1 about its web-rod joint axis
  (the tangent t = z1 x r of the circumcircle at the node) by -(gamma - gamma0), the same sense as
  the fixed node A turns relative to O1 (Rot(y1, -(gamma - gamma0))). For B, t = S4, so
  R_B = R_O1 Rot(S4, -(gamma - gamma0)) R_B0; for E, t = -S6, so R_E = R_O1 Rot(S6, gamma - gamma0) R_E0.
  Eq. (9) as printed uses +(gamma - gamma0) about both S4 and S6, which cannot both hold in a
  motion symmetric about the plane x1-z1; our multibody model realises the reading above.
- Euler convention of R_B0, R_E0: "Rot(x1, a)(y1, b)(z1, c)" is the product Rx(a) Ry(b) Rz(c)
  (successive rotations about the moving axes).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.base.spatial import rot_x, rot_y, rot_z, skew

DEG = np.pi / 180.0

# Initial node orientations relative to O1 (section 3.2), Rx(a) Ry(b) Rz(c).
GAMMA0 = -3.571 * DEG
R_B0_ANGLES = (-92.12 * DEG, 29.56 * DEG, -92.03 * DEG)
R_E0_ANGLES = (-87.09 * DEG, -24.42 * DEG, -91.59 * DEG)

#: Unit yaw about z of the three units (H-ABE, J-AFC, I-ADG), rad, eq. (8).
UNIT_YAW = {"H": 0.0, "J": -2.0 * np.pi / 3.0, "I": 2.0 * np.pi / 3.0}
#: Node letters of each unit: apex, "B-like" node, "E-like" node (images of H, B, E under eq. 8).
UNIT_NODES = {"H": ("H", "B", "E"), "J": ("J", "C", "F"), "I": ("I", "D", "G")}


def rot_axis(k: np.ndarray, angle: float) -> np.ndarray:
    """Eq. (10): rotation by `angle` (rad) about the unit axis k (Rodrigues).

    Args:
        k: unit axis (3,).
        angle: the angle, rad.

    Returns:
        (3, 3) rotation matrix.
    """
    k = np.asarray(k, dtype=float)
    K = skew(k)
    return np.eye(3) + np.sin(angle) * K + (1.0 - np.cos(angle)) * (K @ K)


def euler_xyz(angles: tuple[float, float, float]) -> np.ndarray:
    """Rx(a) Ry(b) Rz(c): the reading of the paper's "Rot(x1, a)(y1, b)(z1, c)".

    Args:
        angles: (a, b, c), rad.

    Returns:
        (3, 3) rotation matrix.
    """
    return rot_x(angles[0]) @ rot_y(angles[1]) @ rot_z(angles[2])


def rpy_angles(R: np.ndarray) -> np.ndarray:
    """Eq. (13): (gamma_x, gamma_y, gamma_z) with R = Rot(z, gz) Rot(y, gy) Rot(x, gx), rad.

    Args:
        R: a rotation matrix (3, 3).

    Returns:
        (3,) angles (gamma_x, gamma_y, gamma_z), rad.
    """
    return np.array(
        [np.arctan2(R[2, 1], R[2, 2]), np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0])), np.arctan2(R[1, 0], R[0, 0])]
    )


def half_angle_beta(l1: float, l2: float) -> float:
    """beta = asin(l2 / (2 l1)) (eq. 6): half the angle B-A-E of the base triangle, rad.

    Args:
        l1: base link A-B (= A-E), m.
        l2: base link B-E, m.

    Returns:
        beta, rad.

    Raises:
        InvalidParameters: l2 outside (0, 2 l1).
    """
    if not (0.0 < l2 < 2.0 * l1):
        raise InvalidParameters("l2", l2, f"needs 0 < l2 < 2 l1 = {2 * l1} m for beta = asin(l2/(2 l1))")
    return float(np.arcsin(l2 / (2.0 * l1)))


@dataclass(frozen=True)
class TrussGeometry:
    """Dimensions of the composite: web rod L, folding links l1 (to A) and l2 (B-E type), m."""

    L: float
    l1: float
    l2: float

    @property
    def beta(self) -> float:
        """Half the angle B-A-E of the base triangle, rad (eq. 6)."""
        return half_angle_beta(self.l1, self.l2)

    def radial(self, which: str) -> np.ndarray:
        """Unit vector from O1 to node A, B or E in O1-x1y1z1 (eq. 6 divided by L sin alpha).

        Args:
            which: "A", "B" or "E".

        Returns:
            (3,) unit vector.
        """
        b2 = 2.0 * self.beta
        return {
            "A": np.array([1.0, 0, 0]),
            "B": np.array([-np.cos(b2), -np.sin(b2), 0]),
            "E": np.array([-np.cos(b2), np.sin(b2), 0]),
        }[which]

    def tangent(self, which: str) -> np.ndarray:
        """z1 x r at node A, B or E (O1 frame): the axis of its web-rod joints; = y1, S4, -S6.

        Args:
            which: "A", "B" or "E".

        Returns:
            (3,) unit vector.
        """
        return np.cross([0.0, 0.0, 1.0], self.radial(which))

    def unit_local(self, alpha: float) -> dict[str, np.ndarray]:
        """Eq. (6) shifted to the origin A: positions of A, B, E, H relative to A in O1 axes, m.

        Args:
            alpha: the fold angle, rad.

        Returns:
            Node -> position (3,), m.
        """
        R = self.L * np.sin(alpha)
        o1 = np.array([-R, 0.0, 0.0])  # O1 relative to A, O1 axes
        return {
            "A": np.zeros(3),
            "B": o1 + R * self.radial("B"),
            "E": o1 + R * self.radial("E"),
            "H": o1 + np.array([0.0, 0.0, self.L * np.cos(alpha)]),
        }

    def unit_local_rate(self, alpha: float) -> dict[str, np.ndarray]:
        """d/d alpha of `unit_local`, m/rad.

        Args:
            alpha: the fold angle, rad.

        Returns:
            Node -> derivative (3,), m/rad.
        """
        dR = self.L * np.cos(alpha)
        d_o1 = np.array([-dR, 0.0, 0.0])
        return {
            "A": np.zeros(3),
            "B": d_o1 + dR * self.radial("B"),
            "E": d_o1 + dR * self.radial("E"),
            "H": d_o1 + np.array([0.0, 0.0, -self.L * np.sin(alpha)]),
        }

    def node_positions(self, alpha: float, gamma: float) -> dict[str, np.ndarray]:
        """Eq. (6)-(8): every node A..J in A-xyz, m.

        Args:
            alpha: the fold angle, rad.
            gamma: the tilt, rad.

        Returns:
            Node -> position (3,), m.
        """
        local = self.unit_local(alpha)
        out = {"A": np.zeros(3)}
        for apex, (h, b, e) in UNIT_NODES.items():
            T = rot_z(UNIT_YAW[apex]) @ rot_y(gamma)
            out.update({h: T @ local["H"], b: T @ local["B"], e: T @ local["E"]})
        return out

    def node_velocities(
        self, alpha: float, gamma: float, alpha_rate: float, gamma_rate: float
    ) -> dict[str, np.ndarray]:
        """Time derivative of eq. (7)-(8), m/s.

        Args:
            alpha: the fold angle, rad.
            gamma: the tilt, rad.
            alpha_rate: its rate, rad/s.
            gamma_rate: its rate, rad/s.

        Returns:
            Node -> velocity (3,), m/s.
        """
        local, dlocal = self.unit_local(alpha), self.unit_local_rate(alpha)
        dRy = np.array([[-np.sin(gamma), 0, np.cos(gamma)], [0, 0, 0], [-np.cos(gamma), 0, -np.sin(gamma)]])
        out = {"A": np.zeros(3)}
        for apex, (h, b, e) in UNIT_NODES.items():
            Rz = rot_z(UNIT_YAW[apex])
            for node, key in ((h, "H"), (b, "B"), (e, "E")):
                out[node] = Rz @ (dRy @ local[key] * gamma_rate + rot_y(gamma) @ dlocal[key] * alpha_rate)
        return out

    def node_rotation(self, node: str, gamma: float, gamma0: float = GAMMA0) -> np.ndarray:
        """Eq. (9) under our reading: orientation of node B or E (unit H-ABE) in A-xyz.

        R = Rot(y, gamma) Rot(t, -(gamma - gamma0)) R_0 with t = S4 (B) or -S6 (E).

        Args:
            node: "B" or "E".
            gamma: the tilt, rad.
            gamma0: the tilt of the reference configuration, rad.

        Returns:
            (3, 3) rotation matrix, A-xyz.

        Raises:
            InvalidParameters: another node.
        """
        if node not in ("B", "E"):
            raise InvalidParameters("node", node, "eq. (9) gives the orientations of B and E")
        r0 = euler_xyz(R_B0_ANGLES if node == "B" else R_E0_ANGLES)
        return rot_y(gamma) @ rot_axis(self.tangent(node), -(gamma - gamma0)) @ r0

    def node_rpy(self, node: str, gamma: float, gamma0: float = GAMMA0) -> np.ndarray:
        """Eq. (11)-(13): RPY angles (gamma_x, gamma_y, gamma_z) of node B or E, rad.

        Args:
            node: "B" or "E".
            gamma: the tilt, rad.
            gamma0: the tilt of the reference configuration, rad.

        Returns:
            (3,) angles, rad.
        """
        return rpy_angles(self.node_rotation(node, gamma, gamma0))
