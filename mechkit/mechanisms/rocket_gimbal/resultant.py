"""The paper's forward kinematics of the engine gimbal: half-angle substitution and Sylvester resultant.

Each actuator's length equation ``|R(alpha, beta) n - o|^2 = L^2`` is, with ``|R n| = |n|``, linear in
the entries of R: ``o^T R n = c``, ``c = (|n|^2 + |o|^2 - L^2) / 2``. The half-angle substitution
``a = tan(alpha/2)``, ``b = tan(beta/2)``, cleared of ``(1 + a^2)(1 + b^2)``, makes it a polynomial of
degree 2 in a and 2 in b (the paper's equations 13, 14). The Sylvester resultant in b of the two
equations is a polynomial in a whose real roots are the alpha of the real assembly modes; for each,
b is the common root of the two quadratics in b (the paper's common-root test).

Degree. The exact eliminant of two bidegree-(2, 2) equations has degree 8 (a 4x4 Sylvester matrix
with entries of degree 2 in a), the number of assembly modes over the complex numbers. The paper
states a degree-16 polynomial (its coefficients k1..k17 are not printed) with a real root that fails
the common-root test, so its equations carried extra factors. `degree16_polynomial` gives one
16-degree form: each equation keeps an extra factor (1 + a^2) (its alpha terms cleared with
(1 + a^2)^2): it equals ``(1 + a^2)^4`` times the eliminant, whose four-fold roots at +-i are where a
degree-16 root finder loses three quarters of its digits. Numpy only; coefficients are computed by
exact polynomial arithmetic on the geometry's numbers (no fitting).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import Polynomial

from mechkit.base.exceptions import InvalidParameters
from mechkit.base.spatial import rot_z
from mechkit.mechanisms.rocket_gimbal.kinematics import GIMBAL_ANGLE, GimbalGeometry, attitude

__all__ = [
    "AssemblyMode",
    "degree16_polynomial",
    "fk_resultant",
    "half_angle_equations",
    "pick_in_range",
    "root_condition",
    "sylvester_matrix",
    "sylvester_resultant",
]

SWING_LIMIT = np.radians(10.0)
"""The paper's operating range: |alpha|, |beta| < 10 deg (rad)."""
DUPLICATE = 1e-7
"""Modes closer than this (rad, |d alpha| + |d beta|) are one mode."""
A_MAX = 1e6
"""Roots with |a| above this are taken as alpha = +-pi, where the half-angle chart fails (skipped)."""
# Rx(t) = _X[0] + cos t _X[1] + sin t _X[2], likewise Ry.
_X = (
    np.diag([1.0, 0.0, 0.0]),
    np.diag([0.0, 1.0, 1.0]),
    np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]),
)
_Y = (
    np.diag([0.0, 1.0, 0.0]),
    np.diag([1.0, 0.0, 1.0]),
    np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [-1.0, 0.0, 0.0]]),
)
# (1 + t^2) * (1, cos, sin) in t = tan(angle/2), ascending coefficients.
_HALF = (np.array([1.0, 0.0, 1.0]), np.array([1.0, 0.0, -1.0]), np.array([0.0, 2.0, 0.0]))


def half_angle_equations(geo: GimbalGeometry, stroke: np.ndarray) -> np.ndarray:
    """Coefficients of the paper's equations (13), (14) after the half-angle substitution.

    Args:
        geo: the geometry.
        stroke: (dlA, dlB), m.

    Returns:
        (2, 3, 3) array C: equation k is ``sum_ij C[k, i, j] a^i b^j = 0`` (a = tan(alpha/2),
        b = tan(beta/2)); units m^2.

    Raises:
        InvalidParameters: strokes that are not two finite values with l0 + dl > 0.
    """
    lengths = geo.nominal_lengths + np.asarray(stroke, dtype=float)
    if lengths.shape != (2,) or not np.all(np.isfinite(lengths)) or np.any(lengths <= 0):
        raise InvalidParameters("stroke", stroke, "need two finite strokes with l0 + dl > 0 (m)")
    turn = rot_z(-GIMBAL_ANGLE)
    out = np.zeros((2, 3, 3))
    for k, (n, o, length) in enumerate(zip(geo.engine_pivots, geo.frame_pivots, lengths)):
        n1, o1 = turn @ n, turn @ o
        for i, ex in enumerate(_X):
            for j, ey in enumerate(_Y):
                out[k] += (o1 @ ex @ ey @ n1) * np.outer(_HALF[i], _HALF[j])
        out[k] -= 0.5 * (n @ n + o @ o - length**2) * np.outer(_HALF[0], _HALF[0])
    return out


def _b_coefficients(eq: np.ndarray) -> list[Polynomial]:
    """An equation (3, 3) as its coefficients of b^0, b^1, b^2, each a polynomial in a."""
    return [Polynomial(eq[:, j]) for j in range(eq.shape[1])]


def sylvester_matrix(eqs: np.ndarray, a: float) -> np.ndarray:
    """The 4x4 Sylvester matrix in b of the two equations at a given a (numeric check of the resultant).

    Args:
        eqs: the (2, 3, 3) coefficients of `half_angle_equations`.
        a: tan(alpha/2).

    Returns:
        (4, 4) matrix.
    """
    (g0, g1, g2), (h0, h1, h2) = ([p(a) for p in _b_coefficients(e)] for e in eqs)
    return np.array([[g2, g1, g0, 0.0], [0.0, g2, g1, g0], [h2, h1, h0, 0.0], [0.0, h2, h1, h0]])


def sylvester_resultant(eqs: np.ndarray) -> Polynomial:
    """The resultant in b of two quadratics in b, as a polynomial in a (degree 8 here).

    Uses the expanded 4x4 Sylvester determinant of g = g2 b^2 + g1 b + g0 and h likewise:
    ``(g2 h0 - g0 h2)^2 - (g2 h1 - g1 h2)(g1 h0 - g0 h1)``.

    Args:
        eqs: the (2, 3, 3) coefficients of `half_angle_equations`.

    Returns:
        The resultant, a polynomial in a = tan(alpha/2).
    """
    (g0, g1, g2), (h0, h1, h2) = (_b_coefficients(e) for e in eqs)
    return (g2 * h0 - g0 * h2) ** 2 - (g2 * h1 - g1 * h2) * (g1 * h0 - g0 * h1)


def degree16_polynomial(eqs: np.ndarray) -> Polynomial:
    """The degree-16 form: the resultant of the equations multiplied by (1 + a^2) each.

    Equal to ``(1 + a^2)^4 * sylvester_resultant(eqs)``; computed from the Sylvester formula on the
    multiplied equations (not by multiplying the result), so its coefficients carry their own rounding.

    Args:
        eqs: the (2, 3, 3) coefficients of `half_angle_equations`.

    Returns:
        The degree-16 polynomial in a.
    """
    clear = Polynomial([1.0, 0.0, 1.0])
    scaled = np.array([[(clear * Polynomial(e[:, j])).coef for j in range(3)] for e in eqs])
    return sylvester_resultant(np.transpose(scaled, (0, 2, 1)))


def root_condition(poly: Polynomial, root: complex) -> float:
    """Normwise condition number of a root x of p: |c|_2 |(1, x, ..., x^n)|_2 / (max(1, |x|) |p'(x)|).

    A perturbation of the coefficient vector of relative 2-norm eps (what a backward-stable root
    finder such as the companion-matrix eigenvalues of `Polynomial.roots` commits) moves the root by
    about cond * eps, measured relative to max(1, |x|) (absolute near 0, where a = tan(alpha/2) ~
    alpha/2): log10(cond) digits are lost. Infinite at a multiple root.

    Args:
        poly: the polynomial p.
        root: one of its roots x.

    Returns:
        The condition number (-); inf at a multiple root.
    """
    x = complex(root)
    powers = np.abs(x) ** np.arange(poly.coef.size)
    slope = max(1.0, abs(x)) * abs(poly.deriv()(x))
    scale = np.linalg.norm(poly.coef) * np.linalg.norm(powers)
    return float(scale / slope) if slope > 0 else float("inf")


@dataclass(frozen=True)
class AssemblyMode:
    """One real solution of the forward kinematics.

    Attributes:
        alpha, beta: hinge angles, rad, in (-pi, pi].
        a: tan(alpha/2) root of the resultant. b: the common root in b.
        b_gap: |difference| of the closest pair of b roots of the two equations (common-root test).
        condition: relative condition number of the root a in the resultant.
        nozzle_z: z component of the nozzle axis R e_z (> 0: nozzle on the +z side as built).
    """

    alpha: float
    beta: float
    a: float
    b: float
    b_gap: float
    condition: float
    nozzle_z: float


def _common_b(eqs: np.ndarray, a: float, gap_tol: float) -> list[tuple[float, float]]:
    """The paper's common-root test at a: every real b that is a root of both quadratics.

    Solves each equation for b and pairs the roots closer than gap_tol (relative). Returns
    (gap, b) per common root, b being the root of the first equation. On the diagonal dlA = dlB
    the two equations coincide at a = 0 and both roots are common.
    """
    powers = np.array([1.0, a, a * a])
    (g0, g1, g2), (h0, h1, h2) = (powers @ e for e in eqs)
    roots_g, roots_h = np.roots([g2, g1, g0]), np.roots([h2, h1, h0])
    common = []
    for x in roots_g:
        if abs(x.imag) > gap_tol * (1.0 + abs(x)) or roots_h.size == 0:
            continue
        gap = float(np.min(np.abs(roots_h - x)) / (1.0 + abs(x)))
        if gap <= gap_tol:
            common.append((gap, float(x.real)))
    return common


def _polish(eqs: np.ndarray, a: float, b: float, steps: int = 3) -> tuple[float, float]:
    """Newton steps on the two half-angle equations in (a, b) (a simple root of the pair)."""
    x = np.array([a, b])
    for _ in range(steps):
        pa, pb = np.array([1.0, x[0], x[0] ** 2]), np.array([1.0, x[1], x[1] ** 2])
        da, db = np.array([0.0, 1.0, 2.0 * x[0]]), np.array([0.0, 1.0, 2.0 * x[1]])
        f = np.array([pa @ e @ pb for e in eqs])
        jac = np.array([[da @ e @ pb, pa @ e @ db] for e in eqs])
        det = jac[0, 0] * jac[1, 1] - jac[0, 1] * jac[1, 0]
        if not np.isfinite(det) or det == 0.0:
            break
        x = x - np.linalg.solve(jac, f)
    return float(x[0]), float(x[1])


def fk_resultant(
    geo: GimbalGeometry,
    stroke: np.ndarray,
    imag_tol: float = 1e-7,
    gap_tol: float = 1e-6,
    polish: bool = True,
) -> list[AssemblyMode]:
    """All real assembly modes for the strokes, by the resultant and the common-root test.

    Args:
        geo: the geometry.
        stroke: (dlA, dlB), m.
        imag_tol: a root a counts as real when |Im a| <= imag_tol * (1 + |a|).
        gap_tol: relative tolerance of the common-root test on b.
        polish: refine each (a, b) by Newton steps on the two half-angle equations (13), (14): this
            restores the digits a near-double root of the resultant loses (near dlA = dlB).

    Returns:
        The real modes, sorted by |alpha| + |beta| (the in-range one first when it exists).
    """
    eqs = half_angle_equations(geo, stroke)
    poly = sylvester_resultant(eqs)
    modes: list[AssemblyMode] = []
    for root in poly.roots():
        if abs(root.imag) > imag_tol * (1.0 + abs(root)) or abs(root) > A_MAX:
            continue
        for gap, b in _common_b(eqs, float(root.real), gap_tol):
            a = float(root.real)
            if polish:
                a, b = _polish(eqs, a, b)
            alpha, beta = 2.0 * np.arctan(a), 2.0 * np.arctan(b)
            if any(abs(alpha - m.alpha) + abs(beta - m.beta) < DUPLICATE for m in modes):
                continue  # a double root of the resultant (two modes sharing alpha) seen twice
            modes.append(
                AssemblyMode(alpha, beta, a, b, gap, root_condition(poly, a), float(attitude(alpha, beta)[2, 2]))
            )
    return sorted(modes, key=lambda m: abs(m.alpha) + abs(m.beta))


def pick_in_range(modes: list[AssemblyMode], limit: float = SWING_LIMIT) -> AssemblyMode:
    """The mode with |alpha|, |beta| < limit (the paper's in-range pick).

    Args:
        modes: the real assembly modes (`fk_resultant`).
        limit: the swing range, rad.

    Returns:
        The mode.

    Raises:
        InvalidParameters: no mode, or more than one, in range (the strokes are outside the swing range).
    """
    inside = [m for m in modes if abs(m.alpha) < limit and abs(m.beta) < limit]
    if len(inside) != 1:
        raise InvalidParameters(
            "stroke",
            [(m.alpha, m.beta) for m in modes],
            f"{len(inside)} assembly modes within +-{np.degrees(limit):.1f} deg",
        )
    return inside[0]
