"""`mechkit.mechanisms.rocket_gimbal.soc`: the supports carry the whole weight at rest."""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.rocket_gimbal.joint_state import joint_state
from mechkit.mechanisms.rocket_gimbal.params import body_inertias
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene
from mechkit.mechanisms.rocket_gimbal.soc import soc_skcs
from mechkit.validation.soc import solve_soc


def test_supports_carry_the_whole_weight_at_rest(mech):
    # Global balance: at rest (null pose, no thrust) the three supports hold exactly the weight.
    scene = SwingScene(amplitude_alpha=0.0, amplitude_beta=0.0, thrust=0.0)
    motion = scene.motion(mech.params, 0.0)
    rest = solve_soc(soc_skcs(mech.params, motion, scene))
    q, v, a = joint_state(mech, motion)
    pin_rest = mech.inverse_dynamics(q, v, a)
    weight = 9.81 * sum(m for m, _, _ in body_inertias(mech.params).values())
    supports = ("bracket_hinge", "a_swing_1", "b_swing_1")
    assert np.isclose(sum(rest.reactions[j][2] for j in supports), weight, rtol=1e-12)
    assert np.isclose(sum(pin_rest.reactions[j].wrench[2] for j in supports), weight, rtol=1e-12)
