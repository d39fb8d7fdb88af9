"""`mechkit.simulation.anchor_reactions`: every joint's reaction from the proximal solve's multipliers
against the core's inverse dynamics on mechkit's own rows (an independent solve), and friction from
them against friction from the inverse dynamics."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit import core
from mechkit.forces import generalized_of_wrenches
from mechkit.simulation.anchor_reactions import AnchorReactions, applies


@pytest.mark.parametrize("name", ["four_bar", "five_bar", "rocket_gimbal"])
def test_reactions_from_the_multipliers_are_the_inverse_dynamics_ones(load_cached, name):
    """At closed states under random efforts and wrenches: the proximal forward dynamics' multipliers give,
    by one RNEA pass, the reactions the core's inverse dynamics computes at the accelerations found
    (the efforts as passive forces: no actuator effort left), to 1e-10 of the largest."""
    m = load_cached(name)
    cm = m.closure_model
    cd = cm.create_data()
    rng = np.random.default_rng(3)
    nv, nj = m.model.nv, m.model.njoints
    worst, data = 0.0, m.model.createData()
    for _ in range(4):
        q = m.assemble(m.home_q[[m.q_index(j) for j in m.actuated]] + rng.uniform(-0.3, 0.3, len(m.actuated)))
        v = m.velocities(q, rng.standard_normal(len(m.actuated)))
        tau, wrenches = rng.standard_normal(nv), np.zeros((nj, 6))
        wrenches[1:] = rng.standard_normal((nj - 1, 6))
        pin.computeJointJacobians(m.model, data, q)  # the placements too
        total = tau + generalized_of_wrenches(m.model, data, wrenches)
        a = core.forward_dynamics(cm, cd, q, v, total, "proximal").a
        anchors = AnchorReactions(cm, cd.legacy["proximal"])
        anchors.at(data)
        mine = anchors(q, v, a, cd.legacy["proximal"].data.lambda_c.copy(), wrenches)
        fx = pin.StdVec_Force()
        for row in wrenches:
            fx.append(pin.Force(row))
        reference = core.inverse_dynamics(cm, cm.create_data(), q, v, a, fx, tau, determinacy_test=False)
        assert np.max(np.abs(reference.effort_values)) <= 1e-9 * max(1.0, np.max(np.abs(tau)))
        worst = max(worst, float(np.max(np.abs(mine - reference.reaction_values)) / np.max(np.abs(mine))))
    assert worst <= 1e-10


def test_generalised_forces_of_wrenches_by_two_passes_are_the_jacobians(load_cached):
    """`AnchorReactions.generalized` (g(q) - rnea(q, 0, 0, f)) against `forces.generalized_of_wrenches`
    (each body's world Jacobian transposed times its wrench) for random wrenches on every body of the
    four-bar: equal to 1e-12 of the largest."""
    m = load_cached("four_bar")
    cm = m.closure_model
    cd = cm.create_data()
    rng = np.random.default_rng(5)
    q = m.assemble([0.7])
    core.forward_dynamics(cm, cd, q, np.zeros(m.model.nv), np.zeros(m.model.nv), "proximal")  # the anchors
    anchors = AnchorReactions(cm, cd.legacy["proximal"])
    data = m.model.createData()
    pin.computeJointJacobians(m.model, data, q)
    wrenches = np.zeros((m.model.njoints, 6))
    wrenches[1:] = rng.standard_normal((m.model.njoints - 1, 6))
    expected = generalized_of_wrenches(m.model, data, wrenches)
    assert np.max(np.abs(anchors.generalized(q, wrenches) - expected)) <= 1e-12 * np.max(np.abs(expected))


def test_the_anchors_apply_where_their_rows_are_mechkits(load_cached):
    """One point anchor per cut (planar revolute, spherical): the anchors give the reactions (tested above);
    two anchors on a revolute axis (the spherical 2-dof's cuts, the tetrahedral unit's): they regularise
    another self-stress, and at a closed state of the spherical 2-dof their reactions differ from the inverse
    dynamics' by a fraction of their size, so the simulation keeps "kkt" and the inverse dynamics there."""
    assert applies(load_cached("ten_bar").closure_model) and applies(load_cached("rocket_gimbal").closure_model)
    assert not applies(load_cached("tetra_3rr3uru").closure_model)
    m = load_cached("spherical_2dof")
    assert not applies(m.closure_model)
    cm = m.closure_model
    cd = cm.create_data()
    q = m.assemble(m.home_q[[m.q_index(j) for j in m.actuated]] + 0.2)
    v, tau = np.zeros(m.model.nv), np.linspace(-1.0, 1.0, m.model.nv)
    a = core.forward_dynamics(cm, cd, q, v, tau, "proximal").a
    anchors = AnchorReactions(cm, cd.legacy["proximal"])
    data = m.model.createData()
    pin.computeJointJacobians(m.model, data, q)
    anchors.at(data)
    mine = anchors(q, v, a, cd.legacy["proximal"].data.lambda_c.copy(), np.zeros((m.model.njoints, 6)))
    reference = core.inverse_dynamics(cm, cm.create_data(), q, v, a, None, tau, determinacy_test=False)
    assert np.max(np.abs(mine - reference.reaction_values)) > 1e-3 * np.max(np.abs(mine))
