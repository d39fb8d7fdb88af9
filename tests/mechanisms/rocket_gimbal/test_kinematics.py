"""`mechkit.mechanisms.rocket_gimbal.kinematics`: the paper's IK, the attitude, the length Jacobian,
Newton FK and the linear rule (numpy only)."""

from __future__ import annotations

import numpy as np
import pytest

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
from mechkit.mechanisms.rocket_gimbal.params import RocketGimbalParams
from mechkit.mechanisms.rocket_gimbal.resultant import (
    fk_resultant,
    half_angle_equations,
    pick_in_range,
)
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene

from .paper_example import GEO, MM, PAPER_ANGLES, PAPER_IK


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
        [(actuator_lengths(GEO, *(x + h * e)) - actuator_lengths(GEO, *(x - h * e))) / (2 * h) for e in np.eye(2)]
    )
    assert np.allclose(length_jacobian(GEO, *x), fd, atol=1e-9)


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
