"""Paths in the kinematic tree (`mechkit.core.tree_paths`) against Pinocchio's own: the columns that move
a joint are the non-zero columns of its Jacobian, and a cut's frames lie in the subtrees Pinocchio lists."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit.catalog import registry
from mechkit.core.tree_paths import subtree_incidence, support_columns


@pytest.mark.parametrize("name", registry.names())
def test_support_columns_are_the_columns_of_the_joint_jacobian(name, load_cached):
    """At a random configuration, a joint's world Jacobian is non-zero exactly on its support columns."""
    m = load_cached(name)
    model, data = m.model, m.model.createData()
    q = pin.integrate(model, m.home_q, 0.3 * np.random.default_rng(2).standard_normal(model.nv))
    pin.computeJointJacobians(model, data, q)
    assert not support_columns(model, 0).any()
    for j in range(1, model.njoints):
        moving = np.abs(pin.getJointJacobian(model, data, j, pin.ReferenceFrame.WORLD)).max(axis=0) > 0
        np.testing.assert_array_equal(support_columns(model, j), moving.astype(float))


@pytest.mark.parametrize("name", registry.names())
def test_subtree_incidence_follows_pinocchios_subtrees(name, load_cached):
    """+1 where frame_b's joint is in joint i's subtree (`model.subtrees`), -1 for frame_a's, summed."""
    m = load_cached(name)
    model = m.model
    incidence = subtree_incidence(model, list(m.cuts))
    assert incidence.shape == (model.njoints, len(m.cuts)) and not incidence[0].any()
    for i in range(1, model.njoints):
        subtree = set(model.subtrees[i])
        for c, cut in enumerate(m.cuts):
            b, a = (model.frames[f].parentJoint in subtree for f in (cut.frame_b, cut.frame_a))
            assert incidence[i, c] == float(b) - float(a), (model.names[i], c)
