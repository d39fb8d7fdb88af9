"""Analytic kinematics of the two-way swinging engine gimbal (Qian et al., reference 004), numpy only.

Frames (the paper's): O-xyz fixed to the gimbal frame, origin at the swing centre O, z along the
nozzle, xOy horizontal; O-x1y1z1 is O-xyz turned by +45 deg about z. The bracket turns by alpha about
Ox1, the engine by beta about the bracket's y axis (Oy2), so the engine's attitude in O-xyz is
``R = Rz(g) Rx(alpha) Ry(beta) Rz(-g)``, g = 45 deg. Actuator A runs from the frame pivot O_A to the
engine pivot A (in the plane xOz), actuator B from O_B to B (in the plane yOz); the inputs are the
strokes ``dl = |A - O_A| - l0``. Everything here is SI (m, rad) in the paper frame O-xyz; this module
knows nothing about URDF or Pinocchio.

Pitch and yaw (the angles the attitude control uses) are the turns of the nozzle axis
``n = R e_z`` about Ox and Oy: ``theta_x = atan2(-n_y, n_z)``, ``theta_y = atan2(n_x, n_z)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import ClosureNotConverged, InvalidParameters, SingularConfiguration
from mechkit.base.spatial import cross, rot_x, rot_y, rot_z

__all__ = [
    "GIMBAL_ANGLE",
    "PAPER_EXAMPLE",
    "RULE_ANGLE",
    "RULE_STROKE",
    "GimbalGeometry",
    "LinearRuleErrors",
    "actuator_lengths",
    "attitude",
    "fk_newton",
    "hinge_axes",
    "length_jacobian",
    "linear_rule",
    "linear_rule_errors",
    "pitch_yaw",
    "strokes",
]

GIMBAL_ANGLE = np.pi / 4
"""Angle (rad) from Ox to the bracket hinge Ox1, about Oz (the paper's 45 deg)."""
#: The paper's linear rule: stroke 110 mm <-> 6.5 deg.
RULE_STROKE, RULE_ANGLE = 0.110, np.radians(6.5)
#: The paper's worked example: strokes (m), its FK answer (rad), its IK lengths of that answer (m).
PAPER_EXAMPLE = {
    "strokes": np.array([-0.060, 0.105]),
    "angles": np.radians([6.6336, -2.0624]),
    "lengths": np.array([1.7828855, 1.9479909]),
}


@dataclass(frozen=True)
class GimbalGeometry:
    """Pivot coordinates of the two actuators, paper frame O-xyz, at the null pose (alpha = beta = 0).

    Attributes:
        engine_pivots: (2, 3) m, rows A and B (points of the engine).
        frame_pivots: (2, 3) m, rows O_A and O_B (points of the gimbal frame).
        nominal_lengths: (2,) m, lA0 and lB0 (actuator lengths at zero stroke).
    """

    engine_pivots: np.ndarray
    frame_pivots: np.ndarray
    nominal_lengths: np.ndarray

    @classmethod
    def reconstruction(
        cls, pivot_radius: float, pivot_offset: float, length_a: float, length_b: float
    ) -> GimbalGeometry:
        """The reconstructed geometry (MECHANISMS.md section 5): actuators parallel to the nozzle axis.

        A = (r, 0, h), B = (0, r, h), O_A = (r, 0, h - lA0), O_B = (0, r, h - lB0).

        Args:
            pivot_radius: r, m, distance of the actuator lines from the nozzle axis.
            pivot_offset: h, m, height of the engine pivots along the nozzle axis from O.
            length_a: lA0, m, actuator A's nominal length.
            length_b: lB0, m, actuator B's nominal length.

        Returns:
            The geometry.

        Raises:
            InvalidParameters: a length that is not finite and > 0.
        """
        for name, value in (
            ("pivot_radius", pivot_radius),
            ("pivot_offset", pivot_offset),
            ("length_a", length_a),
            ("length_b", length_b),
        ):
            if not np.isfinite(value) or value <= 0:
                raise InvalidParameters(name, value, "must be a finite length > 0 (m)")
        r, h = pivot_radius, pivot_offset
        return cls(
            engine_pivots=np.array([[r, 0.0, h], [0.0, r, h]]),
            frame_pivots=np.array([[r, 0.0, h - length_a], [0.0, r, h - length_b]]),
            nominal_lengths=np.array([length_a, length_b]),
        )


def attitude(alpha: float, beta: float) -> np.ndarray:
    """Engine attitude R (3, 3) in O-xyz: about Ox1 by alpha, then about the new y by beta (rad).

    Args:
        alpha: the bracket hinge's angle, rad.
        beta: the engine hinge's angle, rad.

    Returns:
        R (3, 3).
    """
    return rot_z(GIMBAL_ANGLE) @ rot_x(alpha) @ rot_y(beta) @ rot_z(-GIMBAL_ANGLE)


def hinge_axes(alpha: float) -> tuple[np.ndarray, np.ndarray]:
    """Unit axes (O-xyz) of the bracket hinge Ox1 (fixed) and the engine hinge Oy2 (turns with alpha).

    Args:
        alpha: the bracket hinge's angle, rad.

    Returns:
        (Ox1 axis (3,), Oy2 axis (3,)).
    """
    frame = rot_z(GIMBAL_ANGLE)
    return frame[:, 0].copy(), frame @ rot_x(alpha)[:, 1]


def actuator_lengths(geo: GimbalGeometry, alpha: float, beta: float) -> np.ndarray:
    """Closed-form inverse kinematics: lengths (L_A, L_B) in m of the actuators at (alpha, beta) rad.

    Args:
        geo: the geometry.
        alpha: the bracket hinge's angle, rad.
        beta: the engine hinge's angle, rad.

    Returns:
        (L_A, L_B), m.
    """
    moved = geo.engine_pivots @ attitude(alpha, beta).T
    return np.linalg.norm(moved - geo.frame_pivots, axis=1)


def strokes(geo: GimbalGeometry, alpha: float, beta: float) -> np.ndarray:
    """Inverse kinematics as strokes (dlA, dlB) = (L_A - lA0, L_B - lB0), m.

    Args:
        geo: the geometry.
        alpha: the bracket hinge's angle, rad.
        beta: the engine hinge's angle, rad.

    Returns:
        (dlA, dlB), m.
    """
    return actuator_lengths(geo, alpha, beta) - geo.nominal_lengths


def _lengths_and_jacobian(geo: GimbalGeometry, alpha: float, beta: float) -> tuple[np.ndarray, np.ndarray]:
    """(L_A, L_B) m and d(L_A, L_B)/d(alpha, beta) (2, 2) m/rad at one pose."""
    moved = geo.engine_pivots @ attitude(alpha, beta).T
    lengths = np.linalg.norm(moved - geo.frame_pivots, axis=1)
    axes = np.array(hinge_axes(alpha))
    # dL/d(angle) = u . (axis x p) = axis . (p x u) = axis . (o x p) / L
    moments = np.array([cross(o, p) for o, p in zip(geo.frame_pivots, moved)]) / lengths[:, None]
    return lengths, moments @ axes.T


def length_jacobian(geo: GimbalGeometry, alpha: float, beta: float) -> np.ndarray:
    """d(L_A, L_B)/d(alpha, beta), (2, 2) m/rad, analytic (rows: actuators; columns: alpha, beta).

    Args:
        geo: the geometry.
        alpha: the bracket hinge's angle, rad.
        beta: the engine hinge's angle, rad.

    Returns:
        (2, 2) Jacobian, m/rad.
    """
    return _lengths_and_jacobian(geo, alpha, beta)[1]


def fk_newton(
    geo: GimbalGeometry,
    stroke: np.ndarray,
    guess: tuple[float, float] = (0.0, 0.0),
    tol: float = 1e-14,
    max_iter: int = 50,
) -> np.ndarray:
    """Forward kinematics by Newton's method on the two length equations.

    Args:
        geo: the geometry.
        stroke: (dlA, dlB), m.
        guess: initial (alpha, beta), rad; the default (null pose) finds the as-built, in-range mode.
        tol: stop when the Newton step is below tol (rad).
        max_iter: iteration cap.

    Returns:
        (alpha, beta), rad.

    Raises:
        ClosureNotConverged: no convergence within max_iter.
        SingularConfiguration: the length Jacobian is singular on the way.
        InvalidParameters: strokes that are not two finite values with lA0 + dl > 0.
    """
    target = geo.nominal_lengths + np.asarray(stroke, dtype=float)
    if target.shape != (2,) or not np.all(np.isfinite(target)) or np.any(target <= 0):
        raise InvalidParameters("stroke", stroke, "need two finite strokes with lA0 + dl > 0 (m)")
    x = np.array(guess, dtype=float)
    for it in range(1, max_iter + 1):
        lengths, jac = _lengths_and_jacobian(geo, *x)
        det = jac[0, 0] * jac[1, 1] - jac[0, 1] * jac[1, 0]
        if not abs(det) > 1e-12 * np.abs(jac).max() ** 2:
            raise SingularConfiguration(
                float(np.linalg.cond(jac)), "actuator-length Jacobian d(L_A, L_B)/d(alpha, beta)"
            )
        step = np.linalg.solve(jac, target - lengths)
        x += step
        if np.max(np.abs(step)) < tol:
            return x
    residual = float(np.max(np.abs(actuator_lengths(geo, *x) - target)))
    raise ClosureNotConverged(residual, tol, it, "rocket gimbal Newton FK")


def pitch_yaw(alpha: float, beta: float) -> np.ndarray:
    """(theta_x, theta_y) rad: turns of the nozzle axis n = R e_z about Ox (pitch) and Oy (yaw).

    Args:
        alpha: the bracket hinge's angle, rad.
        beta: the engine hinge's angle, rad.

    Returns:
        (theta_x, theta_y), rad.
    """
    n = attitude(alpha, beta)[:, 2]
    return np.array([np.arctan2(-n[1], n[2]), np.arctan2(n[0], n[2])])


def linear_rule(stroke: np.ndarray, stroke_max: float = RULE_STROKE, angle_max: float = RULE_ANGLE) -> np.ndarray:
    """The proportional rule used in practice: |stroke| = stroke_max <-> |angle| = angle_max.

    Actuator B (in the yOz plane) sets pitch theta_x, actuator A (xOz plane) sets yaw theta_y; the
    signs are those of the true small-stroke response (extending A turns the nozzle to -theta_y,
    extending B to +theta_x).

    Args:
        stroke: (..., 2) strokes (dlA, dlB), m.
        stroke_max: the rule's full stroke, m.
        angle_max: the angle at full stroke, rad.

    Returns:
        (..., 2) (theta_x, theta_y) rad.

    Raises:
        InvalidParameters: a stroke_max or angle_max that is not finite and > 0.
    """
    if not (np.isfinite(stroke_max) and stroke_max > 0):
        raise InvalidParameters("stroke_max", stroke_max, "must be a finite stroke > 0 (m)")
    s = np.asarray(stroke, dtype=float)
    k = angle_max / stroke_max
    return np.stack([k * s[..., 1], -k * s[..., 0]], axis=-1)


@dataclass(frozen=True)
class LinearRuleErrors:
    """The linear rule against the exact kinematics over a stroke grid.

    Attributes:
        stroke_a, stroke_b: (n,) grid axes, m.
        exact: (n, n, 2) exact (theta_x, theta_y), rad, indexed [i_a, i_b].
        linear: (n, n, 2) the rule's (theta_x, theta_y), rad.
        worst: largest |exact - linear| over the grid and both angles, rad.
        worst_at: (dlA, dlB) m where it occurs.
        cross_talk: largest |theta_x| with B at rest and |theta_y| with A at rest (the angle the
            rule says is zero), rad.
    """

    stroke_a: np.ndarray
    stroke_b: np.ndarray
    exact: np.ndarray
    linear: np.ndarray
    worst: float
    worst_at: tuple[float, float]
    cross_talk: float


def linear_rule_errors(
    geo: GimbalGeometry, stroke_max: float = RULE_STROKE, angle_max: float = RULE_ANGLE, n: int = 45
) -> LinearRuleErrors:
    """Error map of the linear rule over the square [-stroke_max, stroke_max]^2 (n x n strokes, n odd).

    Args:
        geo: the geometry.
        stroke_max: the square's half width, m.
        angle_max: the rule's angle at full stroke, rad.
        n: grid points per axis (odd).

    Returns:
        The exact and rule angles on the grid, their errors, and the worst error (rad) and where.

    Raises:
        InvalidParameters: n even or below 3.
    """
    if n < 3 or n % 2 == 0:
        raise InvalidParameters("n", n, "need an odd grid size >= 3 (the grid must contain 0)")
    axis = np.linspace(-stroke_max, stroke_max, n)
    exact = np.empty((n, n, 2))
    for i, sa in enumerate(axis):
        guess = (0.0, 0.0)
        for j, sb in enumerate(axis):
            angles = fk_newton(geo, (sa, sb), guess=guess)
            exact[i, j] = pitch_yaw(*angles)
            guess = tuple(angles)
    grid = np.stack(np.meshgrid(axis, axis, indexing="ij"), axis=-1)
    linear = linear_rule(grid, stroke_max, angle_max)
    err = np.abs(exact - linear).max(axis=-1)
    i, j = np.unravel_index(np.argmax(err), err.shape)
    mid = n // 2
    talk = max(np.abs(exact[:, mid, 0]).max(), np.abs(exact[mid, :, 1]).max())
    return LinearRuleErrors(axis, axis, exact, linear, float(err[i, j]), (float(axis[i]), float(axis[j])), float(talk))
