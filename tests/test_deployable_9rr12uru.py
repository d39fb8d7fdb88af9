"""9RR-12URU composite: mobility and the redundant constraint, the 200 s fold against eq. (6)-(8),
and inverse dynamics with its indeterminate part."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.deployable_9rr12uru import DeployableParams
from mechkit.mechanisms.deployable_9rr12uru import redundancy as red
from mechkit.mechanisms.truss.drives import drive_state
from mechkit.mechanisms.truss.fold import fold, fold_times
from mechkit.mechanisms.truss.nodes import node_positions, node_velocity

COARSE = fold_times(25.0)


@pytest.fixture(scope="module")
def mech(load_cached):
    return load_cached("deployable_9rr12uru")


@pytest.fixture(scope="module")
def coarse_fold(mech):
    return fold(mech, COARSE)


def test_model_size(mech):
    assert mech.model.nv == 66 and mech.closure_model.kernel.size == 60 and len(mech.closures) == 12
    assert len(mech.actuated) == 7


def test_mobility_7_with_one_redundant_row_along_the_fold(mech, coarse_fold):
    for sample in coarse_fold:
        mob = mech.mobility(sample.q)
        assert (mob.dof, mob.redundant, mob.rank) == (7, 1, 59)
        assert mob.singular_values[-1] < 1e-12 * mob.singular_values[0] < mob.singular_values[-2]


def test_the_third_chain_is_the_redundant_one(mech):
    q = mech.home_q
    assert red.mobility_without(mech, q, ("EC", "DF", "BG")) == (9, 0)  # three 3-DOF units
    assert red.mobility_without(mech, q, ("EC", "DF")) == (8, 0)
    for chain in ("EC", "DF", "BG"):  # each chain is redundant given the two others (eq. 5)
        assert red.mobility_without(mech, q, (chain,)) == (7, 0)


@pytest.mark.parametrize("i", [0, 4])
def test_the_seventh_dof_is_instantaneous_off_the_symmetric_motions(mech, coarse_fold, i):
    """Second order: on the 7-dim kernel of J, Q(d) = y^T e''[d, d] has 2 positive, 2 negative and
    3 zero eigenvalues; only motions with Q(d) = 0 continue, the paper's fold among them."""
    sample = coarse_fold[i]
    Q, basis = red.second_order_form(mech, sample.q)
    w = np.linalg.eigvalsh(Q)
    big = np.abs(w).max()
    assert w[1] < -0.5 * big and w[5] > 0.5 * big
    assert np.abs(w[2:5]).max() < 1e-3 * big
    c = basis.T @ sample.v
    assert np.linalg.norm(basis @ c - sample.v) < 1e-9 * np.linalg.norm(sample.v)  # the fold is a first-order motion
    assert abs(c @ Q @ c) < 1e-3 * big * (c @ c)


def test_self_stress_is_forces_along_the_middle_hinges(mech, coarse_fold):
    """At t = 0 each URU's share is a pure force along its middle hinge (the paper's eq. 2); later
    the Hooke axes leave the links and moments normal to the hinge join in."""
    for sample in coarse_fold:
        r = red.redundancy(mech, sample.q)
        for cut, (force, moment) in r.self_stress.items():
            assert abs(force @ r.hinge_axes[cut]) == pytest.approx(np.linalg.norm(force), rel=1e-9)
            assert np.linalg.norm(force) > 1e-4  # every rod and chain carries it
            assert abs(moment @ r.hinge_axes[cut]) < 1e-12
            if sample.t == 0.0:
                assert np.linalg.norm(moment) < 1e-12


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


def test_inverse_dynamics_support_balance_and_indeterminate_set(mech, coarse_fold):
    import pinocchio as pin

    sample = coarse_fold[2]
    result = mech.inverse_dynamics(sample.q, sample.v, sample.a)
    # global balance: the supports at A carry the weight and inertia of everything (determinate sum)
    pin.centerOfMass(mech.model, mech.data, sample.q, sample.v, sample.a)
    total = sum(i.mass for i in mech.model.inertias[1:])  # node A is the ground
    g = mech.model.gravity.linear
    support = sum(r.wrench[:3] for r in result.reactions.values() if r.support)
    np.testing.assert_allclose(support, total * (mech.data.acom[0] - g), atol=1e-9 * total * 9.81)
    summary = red.indeterminate_reactions(result)
    # the efforts are determinate; some reaction components are not (one redundant constraint)
    assert summary and all(np.isfinite(r.wrench).all() for r in result.reactions.values())
    for joint in ("EC_M", "DF_M", "BG_M", "AB_M"):
        assert joint in summary


def test_indeterminate_direction_is_the_one_the_core_flags(mech, coarse_fold):
    sample = coarse_fold[1]
    result = mech.inverse_dynamics(sample.q, sample.v, sample.a)
    pattern = red.indeterminate_direction(mech, sample.q)
    assert set(pattern) == set(result.reactions)
    for joint, reaction in result.reactions.items():
        np.testing.assert_array_equal(np.abs(pattern[joint]) < 1e-8, reaction.determinate, err_msg=joint)
    # the self-stress closes through the ground: the three web rods at A push along their hinge axes
    support = sum(pattern[j][:3] for j in ("AH_A", "AJ_A", "AI_A"))
    assert np.linalg.norm(support) < 1e-9 < np.linalg.norm(pattern["AH_A"][:3])


@pytest.mark.slow
def test_full_fold_with_dynamics(mech):
    samples = fold(mech, fold_times(1.0))
    g = mech.params.geometry()
    worst_pos = worst_res = 0.0
    for sample in samples:
        s = drive_state(sample.t)
        expected = g.node_positions(s.alpha, s.gamma)
        worst_pos = max(worst_pos, max(np.abs(p - expected[n]).max() for n, p in node_positions(mech, sample.q).items()))
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


def test_fold_study_matches_the_paper_and_draws_its_figures(mech, tmp_path):
    """The fold against eq. (6)-(13) every 50 s (moved from test_deployable_tools.py) and its five figures."""
    from mechkit.mechanisms.deployable_9rr12uru.figures import fold_figures
    from mechkit.mechanisms.deployable_9rr12uru.studies import fold_study, worst_deviations

    study = fold_study(mech, step=50.0)
    worst = worst_deviations(study)
    assert worst["node_position"] < 1e-9 and worst["closure_residual"] < 1e-10
    assert worst["node_I_speed"] < 1e-10 and worst["node_B_rpy"] < 1e-9
    paths = fold_figures(study, tmp_path)
    for name in ("drives", "node_F", "node_I_speed", "node_B_rpy", "efforts"):
        assert (tmp_path / f"deployable_{name}.png").stat().st_size > 10_000
    assert len(paths) == 5
