"""The 9RR-12URU composite as a mechanism: its size, mobility 7 with one redundant row along the
fold, the 200 s fold against eq. (6)-(8), bad inputs named."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.deployable_9rr12uru import DeployableParams
from mechkit.mechanisms.deployable_9rr12uru import redundancy as red
from mechkit.mechanisms.truss.drives import drive_state
from mechkit.mechanisms.truss.fold import fold, fold_times
from mechkit.mechanisms.truss.nodes import node_positions, node_velocity


def test_model_size(mech):
    assert mech.model.nv == 66 and mech.closure_model.kernel.size == 60 and len(mech.closures) == 12
    assert len(mech.actuated) == 7


def test_mobility_7_with_one_redundant_row_along_the_fold(mech, coarse_fold):
    for sample in coarse_fold:
        mob = mech.mobility(sample.q)
        assert (mob.dof, mob.redundant, mob.rank) == (7, 1, 59)
        assert mob.singular_values[-1] < 1e-12 * mob.singular_values[0] < mob.singular_values[-2]


def test_fold_matches_eq6_to_eq8_closes_and_reaches_the_folded_end(mech, coarse_fold):
    g = mech.params.geometry()
    for sample in coarse_fold:
        s = drive_state(sample.t)
        expected = g.node_positions(s.alpha, s.gamma)
        positions = node_positions(mech, sample.q)
        assert set(positions) == set(expected)
        for node, pos in positions.items():
            np.testing.assert_allclose(pos, expected[node], atol=1e-9, err_msg=f"{node} at t={sample.t}")
        assert np.abs(mech.closure_residual(sample.q)).max() < 1e-10
        velocities = g.node_velocities(s.alpha, s.gamma, s.alpha_rate, s.gamma_rate)
        speed_i = node_velocity(mech, sample.q, sample.v, "I")
        np.testing.assert_allclose(speed_i, velocities["I"], atol=1e-12)
    assert coarse_fold[-1].t == 200.0
    end = drive_state(200.0)
    assert np.degrees(end.alpha) == pytest.approx(8.1557, abs=1e-4)


@pytest.mark.slow
def test_full_fold_with_dynamics(mech):
    samples = fold(mech, fold_times(1.0))
    g = mech.params.geometry()
    worst_pos = worst_res = 0.0
    for sample in samples:
        s = drive_state(sample.t)
        expected = g.node_positions(s.alpha, s.gamma)
        worst_pos = max(
            worst_pos, max(np.abs(p - expected[n]).max() for n, p in node_positions(mech, sample.q).items())
        )
        worst_res = max(worst_res, np.abs(mech.closure_residual(sample.q)).max())
        result = mech.inverse_dynamics(sample.q, sample.v, sample.a)
        assert all(np.isfinite(u) for u in result.efforts.values())
    assert worst_pos < 1e-9 and worst_res < 1e-10


def test_bad_inputs_raise_named_errors(mech):
    with pytest.raises(InvalidParameters, match="l3"):
        DeployableParams(l3=0.1)
    with pytest.raises(InvalidParameters, match="times"):
        fold(mech, np.array([5.0, 3.0]))
    with pytest.raises(InvalidParameters, match="step"):
        fold_times(0.0)
    with pytest.raises(InvalidParameters, match="node"):
        node_velocity(mech, mech.home_q, np.zeros(mech.model.nv), "Z")
    untested = mech.inverse_dynamics(mech.home_q, np.zeros(mech.model.nv), np.zeros(mech.model.nv), determinacy=False)
    with pytest.raises(InvalidParameters, match="result"):
        red.indeterminate_reactions(untested)
