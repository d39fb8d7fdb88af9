"""The paper's drive laws of the fold (Xu et al. 2017, references/003, section 3.2), numpy only.

Fold angle alpha(t) = asin(0.490 cos xi), xi = 0.25 deg/s t + 23.171 deg, and attitude (tilt)
gamma(t) over the 200 s fold, with their first and second time derivatives. Units SI and radians.

Stated reading (see docs/mechanisms/deployable_9rr12uru.md): ``acos`` in the printed law of gamma
gives |gamma|; the text's initial value gamma0 = -3.571 deg (the angle from x to x1 about y, eq. 7)
is what the law gives at t = 0 with the minus sign, so gamma(t) = -acos(...) here (it stays
negative over the 200 s).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.truss.geometry import DEG

# Drive laws of section 3.2 (printed constants).
XI0, XI_RATE = 23.171 * DEG, 0.25 * DEG  # rad, rad/s
ZETA0, ZETA_RATE = 21.574 * DEG, 0.15 * DEG  # rad, rad/s
ALPHA_GAIN = 0.490
GAMMA_A, GAMMA_B, GAMMA_C, GAMMA_D, GAMMA_E = 0.267, 0.172, 0.718, 0.413, 1.392
FOLD_DURATION = 200.0  # s, "200 s of simulation fold it fully"


def alpha_law(t: ArrayLike) -> np.ndarray:
    """alpha(t) = asin(0.490 cos xi), xi = 0.25 deg/s t + 23.171 deg (rad); complex-safe in t.

    Args:
        t: time(s) since the start of the fold, s (complex for complex-step derivatives).

    Returns:
        alpha, rad, of the shape of t.
    """
    xi = XI0 + XI_RATE * t
    return np.arcsin(ALPHA_GAIN * np.cos(xi))


def _alpha_rate_law(t):
    xi = XI0 + XI_RATE * t
    c = ALPHA_GAIN * np.cos(xi)
    return -ALPHA_GAIN * np.sin(xi) * XI_RATE / np.sqrt(1.0 - c * c)


def _gamma_cos(t):
    cx, cz = np.cos(XI0 + XI_RATE * t), np.cos(ZETA0 + ZETA_RATE * t)
    return GAMMA_A * cx * cz + np.sqrt((GAMMA_B * cx**2 - GAMMA_C) * (GAMMA_D * cz**2 - GAMMA_E))


def gamma_law(t: ArrayLike) -> np.ndarray:
    """gamma(t) = -acos(...) (rad; our sign reading, see the module docstring); complex-safe in t.

    Args:
        t: time(s) since the start of the fold, s (complex for complex-step derivatives).

    Returns:
        gamma, rad, of the shape of t.
    """
    return -np.arccos(_gamma_cos(t))


def _gamma_rate_law(t):
    xi, ze = XI0 + XI_RATE * t, ZETA0 + ZETA_RATE * t
    cx, sx, cz, sz = np.cos(xi), np.sin(xi), np.cos(ze), np.sin(ze)
    p, q = GAMMA_B * cx**2 - GAMMA_C, GAMMA_D * cz**2 - GAMMA_E
    dp, dq = -2.0 * GAMMA_B * cx * sx * XI_RATE, -2.0 * GAMMA_D * cz * sz * ZETA_RATE
    dc = GAMMA_A * (-sx * XI_RATE * cz - cx * sz * ZETA_RATE) + (dp * q + p * dq) / (2.0 * np.sqrt(p * q))
    c = _gamma_cos(t)
    return dc / np.sqrt(1.0 - c * c)  # d/dt(-acos c) = +c' / sqrt(1 - c^2)


def _complex_step(f, t: float) -> float:
    h = 1e-30
    return float(np.imag(f(t + 1j * h)) / h)


@dataclass(frozen=True)
class DriveState:
    """The paper's drive angles at one instant: fold alpha and attitude gamma (rad, rad/s, rad/s^2)."""

    t: float
    alpha: float
    gamma: float
    alpha_rate: float
    gamma_rate: float
    alpha_acc: float
    gamma_acc: float


def drive_state(t: float) -> DriveState:
    """alpha(t) = asin(0.490 cos xi), gamma(t) = -acos(...) (our sign reading), with derivatives.

    First derivatives are analytic; second derivatives by complex step of the analytic first ones
    (exact to rounding).

    Args:
        t: time since the start of the fold, s, in [0, `FOLD_DURATION`].

    Returns:
        alpha, gamma (rad) and their first and second derivatives at t.

    Raises:
        InvalidParameters: t outside [0, `FOLD_DURATION`] or not finite.
    """
    t = float(t)
    if not np.isfinite(t) or t < 0.0 or t > FOLD_DURATION:
        raise InvalidParameters("t", t, f"the paper's drive laws are stated for 0 <= t <= {FOLD_DURATION} s")
    return DriveState(
        t,
        float(alpha_law(t)),
        float(gamma_law(t)),
        float(_alpha_rate_law(t)),
        float(_gamma_rate_law(t)),
        _complex_step(_alpha_rate_law, t),
        _complex_step(_gamma_rate_law, t),
    )
