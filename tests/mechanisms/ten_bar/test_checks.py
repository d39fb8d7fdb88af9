"""`mechkit.mechanisms.ten_bar.checks`: kinematics two ways, reactions three ways, the report rows."""

from __future__ import annotations

import pytest

from mechkit.mechanisms.ten_bar import SPEC
from mechkit.mechanisms.ten_bar import checks as tc
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar import lagrange_model as lm
from mechkit.mechanisms.ten_bar import params as tp
from mechkit.mechanisms.ten_bar import soc as ts

from .states import mid_state


# ------------------------------------------------------------------ kinematics two ways
def test_full_closure_and_dimension_reduction_agree(mech):
    worst = tc.kinematics_disagreement(mech, tc.nominal_inputs(mech.params, 21))
    assert worst["full_vs_reduction"] < 1e-10
    assert worst["full_vs_closed_form"] < 1e-10


def test_reactions_three_ways(mech):
    t, q, v = mid_state(mech)
    results = tc.reactions_three_ways(mech, t, q, v)
    assert tc.reaction_disagreement(results) < 1e-8
    inv = mech.inverse_dynamics(q, v, td.PinocchioDeployment(mech).rhs(t, q, v)[0])  # the R5 spring: the mechanism's
    for motor in tp.MOTORS:  # the motor torque is the reaction moment about the axis (-y)
        assert inv.reactions[motor].wrench[4] == pytest.approx(-inv.efforts[motor], rel=1e-10)
    for pair in geo.PAIRS:  # planar pins: in-plane forces and the axis moment are determinate
        assert list(inv.reactions[pair].determinate) == [True, False, True, False, True, False]
    qL, vL = td.lagrange_state(mech.params, q, v, mech)
    L = lm.lagrange_linkage(mech.params)
    _, _, soc = ts.solve(L, qL, vL, L.solve(qL, vL, tp.motor_law(mech.params, t)[2]).qdd)
    assert max(soc.consistency.values()) < 1e-10  # incl. the hub: the passive equation of motion holds


def test_report_rows(mech):
    rows = SPEC.self_checks(mech)
    assert all(value < 1e-8 for value in rows.values()), rows
