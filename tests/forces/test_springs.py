"""`mechkit.forces.springs`: joint springs and dampers as a force element: the load, the power of the
dampers alone, the springs' potential."""

from __future__ import annotations

import pinocchio as pin
import pytest

from mechkit import core, forces
from mechkit.base.exceptions import InvalidParameters

from .states import state


def test_joint_springs_keep_their_behaviour_and_split_their_power(four_bar):
    """The springs' forces are unchanged; as an element, its power is the dampers' alone and its energy the
    springs' potential, whose derivative along v is minus the springs' power."""
    m = four_bar
    springs = forces.JointSprings(m.model, [core.JointSpring("crank", 2.0, 0.3, 0.5, 0.1)])
    s = state(m)
    load = springs.load(s)
    x, rate = s.q[m.q_index("crank")], s.v[m.v_index("crank")]
    assert load.generalized[m.v_index("crank")] == pytest.approx(0.5 - 2.0 * (x - 0.3) - 0.1 * rate)
    assert load.power == pytest.approx(-0.1 * rate**2)
    h = 1e-6
    dV = (
        springs.energy(m.model, None, pin.integrate(m.model, s.q, h * s.v))
        - springs.energy(m.model, None, pin.integrate(m.model, s.q, -h * s.v))
    ) / (2 * h)
    spring_power = (0.5 - 2.0 * (x - 0.3)) * rate
    assert dV == pytest.approx(-spring_power, rel=1e-8)


def test_a_bad_spring_is_refused_by_name(four_bar):
    """An unknown joint and a negative stiffness are named in the error."""
    with pytest.raises(InvalidParameters, match="nowhere"):
        forces.JointSprings(four_bar.model, [core.JointSpring("nowhere", 1.0)])
    with pytest.raises(InvalidParameters, match="spring stiffness of 'crank'"):  # refused by the record itself
        forces.JointSprings(four_bar.model, [core.JointSpring("crank", -1.0)])
