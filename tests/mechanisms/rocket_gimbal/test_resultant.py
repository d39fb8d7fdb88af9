"""`mechkit.mechanisms.rocket_gimbal.resultant`: the paper's FK (Sylvester resultant), its modes, the
double root on the diagonal, against Newton and the IK."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.polynomial import Polynomial

from mechkit.mechanisms.rocket_gimbal.kinematics import (
    fk_newton,
    length_jacobian,
    strokes,
)
from mechkit.mechanisms.rocket_gimbal.resultant import (
    degree16_polynomial,
    fk_resultant,
    half_angle_equations,
    pick_in_range,
    sylvester_matrix,
    sylvester_resultant,
)

from .paper_example import GEO, MM, PAPER_ANGLES, PAPER_IK, PAPER_STROKES

GRID = [np.array([x, y]) * MM for x in np.linspace(-110, 110, 5) for y in np.linspace(-110, 110, 5)]


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


@settings(max_examples=25, deadline=None)
@given(st.floats(-0.11, 0.11), st.floats(-0.11, 0.11))
def test_any_stroke_pair_in_range_has_one_in_range_mode_that_newton_and_ik_confirm(sa, sb):
    stroke = np.array([sa, sb])
    mode = pick_in_range(fk_resultant(GEO, stroke))
    assert np.allclose([mode.alpha, mode.beta], fk_newton(GEO, stroke), atol=1e-9, rtol=0)
    assert np.allclose(strokes(GEO, mode.alpha, mode.beta), stroke, atol=1e-9, rtol=0)
