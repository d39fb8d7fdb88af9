"""`mechkit.mechanisms.rocket_gimbal.checks`: FK three ways over the stroke square, the closure solver's
flipped mode, the dynamics against SOC."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.rocket_gimbal.checks import dynamics_agreement, fk_agreement, fk_closure
from mechkit.mechanisms.rocket_gimbal.kinematics import strokes
from mechkit.mechanisms.rocket_gimbal.params import geometry
from mechkit.mechanisms.rocket_gimbal.resultant import fk_resultant


def test_fk_polynomial_newton_and_closure_solver_agree_over_the_stroke_square(mech):
    # 7 x 7 strokes over +-110 mm, diagonal (double root of the resultant) included
    fk = fk_agreement(mech, n=7)
    assert fk.polynomial_newton < 1e-9 and fk.polynomial_closure < 1e-9 and fk.newton_closure < 1e-9
    assert fk.ik_round_trip < 1e-9
    assert fk.worst_condition < 1e3


def test_closure_solver_reaches_the_flipped_mode_from_its_guess(mech):
    geo = geometry(mech.params)
    stroke = np.array([-0.06, 0.105])
    flipped = [m for m in fk_resultant(geo, stroke) if m.nozzle_z < 0]
    target = min(flipped, key=lambda m: abs(m.alpha) + abs(m.beta))
    guess = {"bracket_hinge": target.alpha + 0.02, "engine_hinge": target.beta - 0.02}
    angles, _ = fk_closure(mech, stroke, guess=guess)
    assert np.allclose(angles, [target.alpha, target.beta], atol=1e-9)
    assert np.allclose(strokes(geo, *angles), stroke, atol=1e-9)


def test_inverse_dynamics_pinocchio_vs_soc_over_a_swing(mech):
    agreement = dynamics_agreement(mech)
    assert agreement.missing == ()  # every joint's reaction is compared
    assert agreement.indeterminate == 0  # spherical cuts with 3 rows: everything determinate
    assert agreement.efforts < 1e-8 and agreement.reactions < 1e-8
    assert agreement.consistency < 1e-10


@pytest.mark.slow
def test_fk_three_ways_on_a_dense_grid(mech):
    fk = fk_agreement(mech, n=21)
    assert max(fk.polynomial_newton, fk.polynomial_closure, fk.newton_closure) < 1e-9
    assert fk.ik_round_trip < 1e-9
