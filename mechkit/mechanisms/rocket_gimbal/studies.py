"""The engine gimbal's studies, as data: the linear rule's error map, the resultant's conditioning and
the swing's dynamics by two methods (`SPEC.studies`; figures in `figures`, numbers in
docs/mechanisms/rocket_gimbal.md).

- `linearisation`: the linear stroke-angle rule (110 mm <-> 6.5 deg) against the exact kinematics
  over the stroke square, and along the paper's Table 1 lines (one stroke held at -10 / -8 mm).
- `resultant_example`, `condition_map`: the resultant forward kinematics at the paper's example
  {-60, 105} mm (the degree-8 eliminant, the degree-16 form, every real root, the digits the form's
  four-fold roots at +-i keep) and over the stroke square (the in-range root's condition number and
  the raw, unpolished root's error against Newton's forward kinematics).
- `swing`: servo forces and every joint's reaction over one period of the swing, Pinocchio's
  constrained RNEA against SOC virtual work.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import Polynomial

from mechkit.mechanism import Mechanism
from mechkit.mechanisms.rocket_gimbal.joint_state import joint_state
from mechkit.mechanisms.rocket_gimbal.kinematics import (
    RULE_ANGLE,
    RULE_STROKE,
    GimbalGeometry,
    LinearRuleErrors,
    fk_newton,
    linear_rule,
    linear_rule_errors,
    pitch_yaw,
)
from mechkit.mechanisms.rocket_gimbal.resultant import (
    AssemblyMode,
    degree16_polynomial,
    fk_resultant,
    half_angle_equations,
    pick_in_range,
    root_condition,
    sylvester_resultant,
)
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene, thrust_fext
from mechkit.mechanisms.rocket_gimbal.soc import soc_skcs
from mechkit.validation.soc import solve_soc

#: The paper's example strokes (dlA, dlB), m.
EXAMPLE_STROKES = (-0.060, 0.105)
#: The joints on the gimbal frame: the bracket's bearings and the servos' frame pivots.
SUPPORTS = ("bracket_hinge", "a_swing_1", "b_swing_1")


@dataclass(frozen=True)
class Linearisation:
    """The linear rule against the exact kinematics.

    Attributes:
        errors: the error map over the stroke square.
        sweep: (m,) swept stroke along the Table 1 lines, m.
        lines: Table 1 line ("dlA = -10 mm", "dlB = -8 mm") -> (m, 2) exact - linear (theta_x, theta_y), rad.
    """

    errors: LinearRuleErrors
    sweep: np.ndarray
    lines: dict[str, np.ndarray]


def linearisation(geo: GimbalGeometry, n: int = 45, line_points: int = 89) -> Linearisation:
    """The linear rule's error map on an n x n stroke grid (n odd) and along the Table 1 lines.

    Args:
        geo: the gimbal's geometry.
        n: grid points per stroke axis (odd: the grid holds the null pose).
        line_points: samples along each Table 1 line.

    Returns:
        The error map, the rule along the Table 1 lines and its errors.
    """
    sweep = np.linspace(-RULE_STROKE, RULE_STROKE, line_points)
    held = {"dlA = -10 mm": lambda s: np.array([-0.010, s]), "dlB = -8 mm": lambda s: np.array([s, -0.008])}
    lines = {
        k: np.array([pitch_yaw(*fk_newton(geo, at(s))) - linear_rule(at(s)) for s in sweep]) for k, at in held.items()
    }
    return Linearisation(linear_rule_errors(geo, RULE_STROKE, RULE_ANGLE, n), sweep, lines)


def linearisation_summary(study: Linearisation) -> dict[str, float | tuple[float, float]]:
    """The numbers the docs quote: worst error (deg, % of 6.5 deg) and where (mm), cross-talk (deg),
    worst error along the Table 1 lines (deg).

    Args:
        study: the linearisation study.

    Returns:
        Name -> value.
    """
    e = study.errors
    return {
        "worst_deg": float(np.degrees(e.worst)),
        "worst_percent": float(100 * e.worst / RULE_ANGLE),
        "worst_at_mm": tuple(float(1e3 * x) for x in e.worst_at),
        "cross_talk_deg": float(np.degrees(e.cross_talk)),
        "table1_lines_worst_deg": float(np.degrees(max(np.abs(v).max() for v in study.lines.values()))),
    }


@dataclass(frozen=True)
class ResultantExample:
    """The resultant forward kinematics at one stroke pair.

    Attributes:
        eliminant: the degree-8 eliminant in a = tan(alpha / 2).
        degree16: the degree-16 form.
        modes: every real assembly mode (polished).
        pick: the in-range mode.
        spurious_roots: the degree-16 form's roots near +-i (4-fold each).
        scatter: how far they scatter from +-i.
        real_roots_difference: largest relative difference of the real roots, degree 16 vs degree 8.
    """

    eliminant: Polynomial
    degree16: Polynomial
    modes: list[AssemblyMode]
    pick: AssemblyMode
    spurious_roots: np.ndarray
    scatter: float
    real_roots_difference: float


def resultant_example(geo: GimbalGeometry, stroke: tuple[float, float] = EXAMPLE_STROKES) -> ResultantExample:
    """Both polynomials, every real root and the in-range pick at the strokes (m; default: the paper's).

    Args:
        geo: the geometry.
        stroke: (dlA, dlB), m.

    Returns:
        The degree-8 and degree-16 polynomials, the real modes, the pick and the spurious roots.
    """
    stroke = np.asarray(stroke, dtype=float)
    eqs = half_angle_equations(geo, stroke)
    p8, p16 = sylvester_resultant(eqs), degree16_polynomial(eqs)
    modes = fk_resultant(geo, stroke)
    roots16 = p16.roots()
    spurious = roots16[np.abs(np.abs(roots16.imag) - 1.0) < 1e-2]
    real16 = np.sort(roots16[np.abs(roots16.imag) < 1e-7].real)
    real8 = np.sort([m.a for m in fk_resultant(geo, stroke, polish=False)])
    return ResultantExample(
        p8,
        p16,
        modes,
        pick_in_range(modes),
        spurious,
        float(np.abs(spurious - 1j * np.sign(spurious.imag)).max()),
        float(np.abs(real16 / real8 - 1).max()),
    )


@dataclass(frozen=True)
class ConditionMap:
    """The in-range root over the stroke square.

    Attributes:
        axis: (n,) grid axis, m (both strokes).
        condition: (n, n) condition number of the in-range root of the eliminant ([i_a, i_b]; nan: none).
        raw_error: (n, n) max |alpha, beta of the raw root - Newton's| (rad).
    """

    axis: np.ndarray
    condition: np.ndarray
    raw_error: np.ndarray

    @property
    def off_diagonal(self) -> np.ndarray:
        """(n, n) mask of the grid points with dlA != dlB (on the diagonal the in-range root is double)."""
        return ~np.eye(len(self.axis), dtype=bool)


def condition_map(geo: GimbalGeometry, n: int = 41) -> ConditionMap:
    """The in-range root's condition and raw error on an n x n grid of the stroke square.

    Args:
        geo: the geometry.
        n: grid points per stroke axis.

    Returns:
        The grid, the condition numbers and the raw errors (rad).
    """
    axis = np.linspace(-RULE_STROKE, RULE_STROKE, n)
    cond = np.full((n, n), np.nan)
    raw_err = np.full((n, n), np.nan)
    for i, sa in enumerate(axis):
        for j, sb in enumerate(axis):
            s = np.array([sa, sb])
            newton = fk_newton(geo, s)
            modes = [m for m in fk_resultant(geo, s, polish=False) if abs(m.alpha) < 0.2 and abs(m.beta) < 0.2]
            if not modes:
                continue
            best = min(modes, key=lambda m: abs(m.alpha - newton[0]) + abs(m.beta - newton[1]))
            cond[i, j] = best.condition
            raw_err[i, j] = max(abs(best.alpha - newton[0]), abs(best.beta - newton[1]))
    return ConditionMap(axis, cond, raw_err)


@dataclass(frozen=True)
class Conditioning:
    """The resultant's conditioning: the paper's example and the map over the stroke square."""

    example: ResultantExample
    grid: ConditionMap


def conditioning(geo: GimbalGeometry, n: int = 41) -> Conditioning:
    """`resultant_example` at the paper's strokes and `condition_map` on an n x n grid.

    Args:
        geo: the geometry.
        n: grid points per stroke axis.

    Returns:
        Both.
    """
    return Conditioning(resultant_example(geo), condition_map(geo, n))


def conditioning_lines(study: Conditioning) -> list[str]:
    """The example's polynomials and roots, and the map's figures, as text.

    Args:
        study: the conditioning study.

    Returns:
        Text lines.
    """
    ex, grid = study.example, study.grid
    out = [
        "paper example {-60, 105} mm",
        f"  degree-8 eliminant coefficients (a^0..a^8): {np.array2string(ex.eliminant.coef, precision=6)}",
        f"  coefficient range max/min |c|: {np.abs(ex.eliminant.coef).max() / np.abs(ex.eliminant.coef).min():.3g}",
    ]
    for m in ex.modes:
        side = "nozzle +z (as built)" if m.nozzle_z > 0.5 else ("flipped" if m.nozzle_z < 0 else "sideways")
        out.append(
            f"  a = {m.a:+.10f}  alpha = {np.degrees(m.alpha):+11.6f} deg  beta = {np.degrees(m.beta):+11.6f} deg"
            f"  cond8 = {m.condition:6.2f}  cond16 = {root_condition(ex.degree16, m.a):6.2f}  {side}"
        )
    out.append(
        f"  in-range pick: alpha, beta = {np.degrees(ex.pick.alpha):.6f}, {np.degrees(ex.pick.beta):.6f} deg"
        " (paper: 6.6336, -2.0624 deg)"
    )
    out.append(
        f"  degree-16 form: {ex.spurious_roots.size} roots near +-i (4-fold), scattered by {ex.scatter:.2e}"
        f" (eps^(1/4) = {np.finfo(float).eps ** 0.25:.1e}): {-np.log10(ex.scatter):.1f} of 16 digits left"
    )
    out.append(f"  real roots, degree 16 vs degree 8: max relative difference {ex.real_roots_difference:.1e}")
    n, off = len(grid.axis), grid.off_diagonal
    out.append(f"stroke square +-{1e3 * RULE_STROKE:.0f} mm, {n} x {n}:")
    out.append(
        f"  in-range root condition number: median {np.nanmedian(grid.condition):.2f}, max off the diagonal"
        f" {np.nanmax(grid.condition[off]):.3g}, on the diagonal dlA = dlB: {np.nanmax(grid.condition[~off]):.3g}"
        " (double root)"
    )
    out.append(
        f"  raw (unpolished) root vs Newton FK: max {np.nanmax(grid.raw_error):.2e} rad off-diagonal"
        f" {np.nanmax(grid.raw_error[off]):.2e} rad; polished: see the tests (< 1e-9 rad)"
    )
    return out


@dataclass(frozen=True)
class Swing:
    """One period of the swing by two methods.

    Attributes:
        times: (n,) s.
        actuated: the servo stroke joints.
        efforts: method ("pinocchio", "soc") -> (n, 2) servo forces (N, `actuated` order).
        supports: method -> (n, 3, 6) world wrenches of `SUPPORTS` (N, N m).
        relative_difference: (n,) worst relative difference of every effort and joint reaction,
            each relative to its own size.
    """

    times: np.ndarray
    actuated: tuple[str, ...]
    efforts: dict[str, np.ndarray]
    supports: dict[str, np.ndarray]
    relative_difference: np.ndarray


def swing(mech: Mechanism, n: int = 101) -> Swing:
    """Servo forces and every joint's reaction over one period at n instants: Pinocchio vs SOC.

    Args:
        mech: the gimbal.
        n: instants over the period.

    Returns:
        The times, servo forces (N) and support forces by method.
    """
    scene = SwingScene()
    times = np.linspace(0.0, 1.0 / scene.frequency, n)
    efforts, supports, rel = {"pinocchio": [], "soc": []}, {"pinocchio": [], "soc": []}, []
    for t in times:
        motion = scene.motion(mech.params, t)
        q, v, a = joint_state(mech, motion)
        r = mech.inverse_dynamics(q, v, a, fext=thrust_fext(mech, q, scene))
        s = solve_soc(soc_skcs(mech.params, motion, scene))
        efforts["pinocchio"].append([r.efforts[j] for j in mech.actuated])
        efforts["soc"].append([s.efforts[j] for j in mech.actuated])
        supports["pinocchio"].append([r.reactions[j].wrench for j in SUPPORTS])
        supports["soc"].append([s.reactions[j] for j in SUPPORTS])
        diffs = [abs(r.efforts[j] - s.efforts[j]) / abs(r.efforts[j]) for j in mech.actuated]
        diffs += [
            np.abs(r.reactions[j].wrench - s.reactions[j]).max() / np.abs(r.reactions[j].wrench).max()
            for j in r.reactions
        ]
        rel.append(max(diffs))
    return Swing(
        times,
        tuple(mech.actuated),
        {k: np.array(x) for k, x in efforts.items()},
        {k: np.array(x) for k, x in supports.items()},
        np.array(rel),
    )


def swing_summary(study: Swing) -> dict[str, float]:
    """Peaks (kN, MN) and the worst relative difference of the two methods.

    Args:
        study: the swing study.

    Returns:
        Name -> value.
    """
    pin_u, pin_f = study.efforts["pinocchio"], study.supports["pinocchio"]
    bearing = np.linalg.norm(pin_f[:, 0, :3], axis=1)
    return {
        "peak servo force (kN)": float(np.abs(pin_u).max() / 1e3),
        "bearing force min (MN)": float(bearing.min() / 1e6),
        "bearing force max (MN)": float(bearing.max() / 1e6),
        "peak servo pivot force (kN)": float(np.linalg.norm(pin_f[:, 1:, :3], axis=2).max() / 1e3),
        "worst relative difference Pinocchio vs SOC": float(max(study.relative_difference)),
    }


def linearisation_lines(study: Linearisation) -> list[str]:
    """`linearisation_summary` as text lines.

    Args:
        study: the linearisation study.

    Returns:
        Text lines.
    """
    return [f"{key}: {value}" for key, value in linearisation_summary(study).items()]


def swing_lines(study: Swing) -> list[str]:
    """`swing_summary` as text lines.

    Args:
        study: the swing study.

    Returns:
        Text lines.
    """
    return [f"{key}: {value:.6g}" for key, value in swing_summary(study).items()]
