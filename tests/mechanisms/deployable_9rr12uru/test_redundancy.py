"""`mechkit.mechanisms.deployable_9rr12uru.redundancy`: the redundant chain, the instantaneous seventh
DOF, the self-stress, and the indeterminate reactions."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.deployable_9rr12uru import redundancy as red


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
