"""`mechkit.mechanisms.truss.fold` on the unit: the fold matches eq. (6)-(7), closes, follows the
web-joint laws, and takes the whole fold in one requested step."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.truss.drives import drive_state
from mechkit.mechanisms.truss.fold import fold
from mechkit.mechanisms.truss.joint_state import web_joint_motion
from mechkit.mechanisms.truss.nodes import node_positions


def test_unit_fold_matches_eq6_eq7_and_closes(unit, unit_fold):
    p = unit.params
    for sample in unit_fold:
        s = drive_state(sample.t)
        expected = p.geometry().node_positions(s.alpha, s.gamma)
        for node, pos in node_positions(unit, sample.q).items():
            np.testing.assert_allclose(pos, expected[node], atol=1e-9)
        assert np.abs(unit.closure_residual(sample.q)).max() < 1e-10
        angles, rates, accs = web_joint_motion(p, s)
        for joint in angles:
            k = unit.v_index(joint)
            assert sample.q[unit.q_index(joint)] == pytest.approx(angles[joint], abs=1e-9)
            assert sample.v[k] == pytest.approx(rates[joint], abs=1e-11)
            assert sample.a[k] == pytest.approx(accs[joint], abs=1e-12)


def test_fold_continuation_takes_the_whole_fold_in_one_requested_step(unit):
    (end,) = fold(unit, np.array([200.0]))
    s = drive_state(200.0)
    expected = unit.params.geometry().node_positions(s.alpha, s.gamma)
    for node, pos in node_positions(unit, end.q).items():
        np.testing.assert_allclose(pos, expected[node], atol=1e-9)
