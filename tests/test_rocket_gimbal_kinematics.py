"""The engine gimbal's analytic kinematics: IK, the resultant FK, Newton FK, the linear rule (numpy only)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.polynomial import Polynomial

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.rocket_gimbal.body_motion import gimbal_motion
from mechkit.mechanisms.rocket_gimbal.kinematics import (
    PAPER_EXAMPLE,
    RULE_ANGLE,
    RULE_STROKE,
    actuator_lengths,
    attitude,
    fk_newton,
    length_jacobian,
    linear_rule,
    pitch_yaw,
    strokes,
)
from mechkit.mechanisms.rocket_gimbal.params import RocketGimbalParams, geometry
from mechkit.mechanisms.rocket_gimbal.resultant import (
    degree16_polynomial,
    fk_resultant,
    half_angle_equations,
    pick_in_range,
    sylvester_matrix,
    sylvester_resultant,
)
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene

GEO = geometry(RocketGimbalParams())
MM = 1e-3
GRID = [np.array([x, y]) * MM for x in np.linspace(-110, 110, 5) for y in np.linspace(-110, 110, 5)]
# The paper's example: strokes {-60, 105} mm, its FK answer, and its IK of that answer as strokes.
PAPER_STROKES, PAPER_ANGLES = PAPER_EXAMPLE["strokes"], PAPER_EXAMPLE["angles"]
PAPER_IK = np.array([-60.1145, 104.9909]) * MM


def test_ik_reproduces_the_papers_printed_lengths():
    lengths = actuator_lengths(GEO, *PAPER_ANGLES)
    # printed to 0.1 um: L_A = 1782.8855 mm, L_B = 1947.9909 mm
    assert np.allclose(lengths, PAPER_EXAMPLE["lengths"], atol=0.06e-6)
    assert np.allclose(strokes(GEO, *PAPER_ANGLES), PAPER_IK, atol=0.06e-6)


def test_attitude_is_a_rotation_about_the_two_hinges():
    R = attitude(0.3, -0.2)
    assert np.allclose(R @ R.T, np.eye(3), atol=1e-15) and np.isclose(np.linalg.det(R), 1.0)
    x1 = np.array([1.0, 1.0, 0.0]) / np.sqrt(2)
    assert np.allclose(attitude(0.3, 0.0) @ x1, x1)  # alpha turns about Ox1
    y1 = np.array([-1.0, 1.0, 0.0]) / np.sqrt(2)
    assert np.allclose(attitude(0.0, -0.2) @ y1, y1)  # beta about Oy1 (= Oy2 at alpha = 0)


def test_length_jacobian_matches_finite_differences():
    x, h = np.array([0.07, -0.05]), 1e-6
    fd = np.column_stack(
        [
            (actuator_lengths(GEO, *(x + h * e)) - actuator_lengths(GEO, *(x - h * e))) / (2 * h)
            for e in np.eye(2)
        ]
    )
    assert np.allclose(length_jacobian(GEO, *x), fd, atol=1e-9)


def test_sylvester_formula_is_the_determinant_of_the_sylvester_matrix():
    eqs = half_angle_equations(GEO, PAPER_STROKES)
    res = sylvester_resultant(eqs)
    assert res.degree() == 8
    for a in (-3.0, -0.4, 0.05, 1.7):
        det = np.linalg.det(sylvester_matrix(eqs, a))
        assert abs(res(a) - det) <= 1e-12 * max(1.0, abs(det))


def test_degree16_form_is_the_eliminant_times_one_plus_a_squared_to_the_fourth():
    eqs = half_angle_equations(GEO, PAPER_STROKES)
    p8, p16 = sylvester_resultant(eqs), degree16_polynomial(eqs)
    assert p16.degree() == 16
    quotient, remainder = divmod(p16, Polynomial([1.0, 0.0, 1.0]) ** 4)
    scale = np.abs(p16.coef).max()
    assert np.abs(remainder.coef).max() < 1e-13 * scale
    assert np.abs((quotient - p8).coef).max() < 1e-13 * scale
    real8 = np.sort([m.a for m in fk_resultant(GEO, PAPER_STROKES)])
    roots16 = p16.roots()
    real16 = np.sort(roots16[np.abs(roots16.imag) < 1e-7].real)
    assert np.allclose(real8, real16, rtol=1e-10)


def test_every_real_mode_closes_both_actuators():
    modes = fk_resultant(GEO, PAPER_STROKES)
    assert len(modes) >= 2
    for m in modes:
        assert np.allclose(strokes(GEO, m.alpha, m.beta), PAPER_STROKES, atol=1e-11)
    # nozzle on its own side (in range) and a flipped mode both exist
    assert modes[0].nozzle_z > 0.9 and min(m.nozzle_z for m in modes) < 0


def test_paper_example_differs_by_the_papers_own_round_trip_error():
    ours = pick_in_range(fk_resultant(GEO, PAPER_STROKES))
    delta = PAPER_ANGLES - np.array([ours.alpha, ours.beta])
    assert np.all(np.abs(delta) < np.radians(0.006))
    # The paper's answer is off ours by what its own IK round trip shows: J delta = its stroke error.
    predicted = length_jacobian(GEO, ours.alpha, ours.beta) @ delta
    assert np.allclose(predicted, PAPER_IK - PAPER_STROKES, atol=3e-6)


@pytest.mark.parametrize("stroke", GRID, ids=lambda s: f"{s[0] / MM:+.0f},{s[1] / MM:+.0f}mm")
def test_resultant_and_newton_agree_and_ik_inverts_them(stroke):
    mode = pick_in_range(fk_resultant(GEO, stroke))
    newton = fk_newton(GEO, stroke)
    assert np.allclose([mode.alpha, mode.beta], newton, atol=1e-9, rtol=0)
    assert np.allclose(strokes(GEO, mode.alpha, mode.beta), stroke, atol=1e-9, rtol=0)
    assert np.allclose(strokes(GEO, *newton), stroke, atol=1e-9, rtol=0)
    if stroke[0] != stroke[1]:
        assert mode.condition < 1e3  # off the diagonal the in-range root loses at most three digits


@pytest.mark.parametrize("stroke", [0.0, 0.05, -0.1])
def test_on_the_diagonal_two_modes_share_alpha_zero_a_double_root(stroke):
    # Mirror symmetry in the plane (Ox1, Oz): with dlA = dlB both equations coincide at alpha = 0,
    # so the resultant has a double root at a = 0 (the in-range mode and a flipped one).
    eqs = half_angle_equations(GEO, [stroke, stroke])
    assert np.allclose(eqs[0][0], eqs[1][0], rtol=1e-12, atol=1e-15)
    res = sylvester_resultant(eqs)
    scale = np.abs(res.coef).max()
    assert abs(res.coef[0]) < 1e-13 * scale and abs(res.coef[1]) < 1e-13 * scale
    alphas = [m.alpha for m in fk_resultant(GEO, [stroke, stroke]) if abs(m.alpha) < 1e-9]
    assert len(alphas) == 2


def test_linear_rule_worst_error_on_the_papers_lines_is_its_printed_04_deg():
    sweep = np.linspace(-RULE_STROKE, RULE_STROKE, 45)
    lines = [np.array([-10 * MM, s]) for s in sweep] + [np.array([s, -8 * MM]) for s in sweep]
    worst = max(np.max(np.abs(pitch_yaw(*fk_newton(GEO, s)) - linear_rule(s))) for s in lines)
    assert round(np.degrees(worst), 1) == 0.4  # 0.4 deg / 6.5 deg = 6.15 % in the paper


def test_swing_is_asymmetric_in_sign_and_couples_pitch_and_yaw():
    up = pitch_yaw(*fk_newton(GEO, [0.0, RULE_STROKE]))
    down = pitch_yaw(*fk_newton(GEO, [0.0, -RULE_STROKE]))
    assert up[0] > 0 > down[0] and abs(up[0]) - abs(down[0]) > np.radians(0.2)
    assert abs(up[1]) > np.radians(0.1) and abs(down[1]) > np.radians(0.1)
    assert abs(abs(up[0]) - RULE_ANGLE) < np.radians(0.5)


def test_bad_strokes_raise_named_errors():
    with pytest.raises(InvalidParameters, match="stroke"):
        fk_newton(GEO, [np.nan, 0.0])
    with pytest.raises(InvalidParameters, match="stroke"):
        half_angle_equations(GEO, [-2.0, 0.0])
    with pytest.raises(InvalidParameters, match="stroke"):
        pick_in_range(fk_resultant(GEO, [0.6, -0.6]))
    with pytest.raises(InvalidParameters, match="pivot_offset"):
        RocketGimbalParams(pivot_offset=1.843)
    with pytest.raises(InvalidParameters, match="rates"):
        gimbal_motion(GEO, [0.0, 0.0], [np.inf, 0.0], [0.0, 0.0])
    with pytest.raises(InvalidParameters, match="frequency"):
        SwingScene(frequency=0.0)
    with pytest.raises(InvalidParameters, match="stroke_max"):
        linear_rule([0.0, 0.0], stroke_max=0.0)


def test_analytic_motion_matches_finite_differences_of_the_geometry():
    scene, t, h = SwingScene(), 0.37, 1e-5
    motions = [gimbal_motion(GEO, *scene.angles(t + k * h)) for k in (-1, 0, 1)]
    for i in range(2):
        legs = [m.legs[i] for m in motions]
        rate_fd = (legs[2].length - legs[0].length) / (2 * h)
        acc_fd = (legs[2].length - 2 * legs[1].length + legs[0].length) / h**2
        assert np.isclose(legs[1].length_rate, rate_fd, rtol=1e-7, atol=1e-9)
        assert np.isclose(legs[1].length_acc, acc_fd, rtol=1e-4, atol=1e-5)
        hooke_fd = (legs[2].hooke - legs[0].hooke) / (2 * h)
        hooke_acc_fd = (legs[2].hooke - 2 * legs[1].hooke + legs[0].hooke) / h**2
        assert np.allclose(legs[1].hooke_rate, hooke_fd, rtol=1e-7, atol=1e-9)
        assert np.allclose(legs[1].hooke_acc, hooke_acc_fd, rtol=1e-4, atol=1e-5)
        # the length and the Hooke angles are those of the closed-form IK
        assert np.isclose(legs[1].length, actuator_lengths(GEO, *motions[1].angles)[i], rtol=1e-15)
    # engine angular acceleration: d(omega)/dt by finite differences
    alpha_fd = (motions[2].omega - motions[0].omega) / (2 * h)
    assert np.allclose(motions[1].alpha, alpha_fd, rtol=1e-6, atol=1e-8)


@settings(max_examples=25, deadline=None)
@given(st.floats(-0.11, 0.11), st.floats(-0.11, 0.11))
def test_any_stroke_pair_in_range_has_one_in_range_mode_that_newton_and_ik_confirm(sa, sb):
    stroke = np.array([sa, sb])
    mode = pick_in_range(fk_resultant(GEO, stroke))
    assert np.allclose([mode.alpha, mode.beta], fk_newton(GEO, stroke), atol=1e-9, rtol=0)
    assert np.allclose(strokes(GEO, mode.alpha, mode.beta), stroke, atol=1e-9, rtol=0)
