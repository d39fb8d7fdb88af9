"""`mechkit.history.axes`: the world axes of every joint along a motion, against what the motion itself shows:
a tree joint's axis is the direction its child body turns (or slides) when only that joint moves (finite
differences of the placements), a revolute cut's axis the direction of the relative angular velocity of
its two frames along any closed motion; a joint of several freedoms has none."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit import core
from mechkit.history.axes import JointAxes


def _poses(m, offsets):
    """Assembled poses near home, the actuated joints moved by each offset (rad or m)."""
    home = {j: m.home_q[m.q_index(j)] for j in m.actuated}
    return np.array([m.assemble({j: x + d for j, x in home.items()}, guess=m.home_q) for d in offsets])


def _world_axes(m, Q):
    cm = m.closure_model
    G, J, _ = core.kinematic_pass(cm, cm.create_data(), Q)
    return JointAxes(m).world(J, G)


@pytest.mark.parametrize(
    "name, offsets", [("spherical_2dof", (0.0, 0.1, -0.15)), ("rocket_gimbal", (0.0, 0.01, -0.02))]
)
def test_tree_axes_are_the_directions_their_bodies_move(load_cached, name, offsets):
    m = load_cached(name)
    Q = _poses(m, offsets)
    axes = _world_axes(m, Q)
    model, data = m.model, m.model.createData()
    h = 1e-7
    for q, found in zip(Q, axes):
        assert np.allclose(np.linalg.norm(found[: model.njoints - 1], axis=1), 1.0, atol=1e-12)
        for j in range(1, model.njoints):
            jm = model.joints[j]
            moved = q.copy()
            moved[jm.idx_q] += h
            pin.forwardKinematics(model, data, q)
            before = data.oMi[j].copy()
            pin.forwardKinematics(model, data, moved)
            after = data.oMi[j]
            if jm.shortname().startswith("JointModelP"):
                expected = (after.translation - before.translation) / h
            else:
                expected = pin.log3(after.rotation @ before.rotation.T) / h
            assert np.allclose(found[j - 1], expected, atol=1e-6), (name, model.names[j])


def test_revolute_cut_axes_carry_the_relative_rotation(load_cached):
    """The spherical 2-DoF's cuts r13, r23 along closed motions: the relative angular velocity of frame_b to
    frame_a is parallel to the cut's axis (its component across the axis vanishes)."""
    m = load_cached("spherical_2dof")
    Q = _poses(m, (0.0, 0.1, -0.15))
    axes = _world_axes(m, Q)
    model, data = m.model, m.model.createData()
    n_tree = model.njoints - 1
    for q, found in zip(Q, axes):
        v = m.velocities(q, [0.7, -0.4])
        pin.forwardKinematics(model, data, q, v)
        pin.updateFramePlacements(model, data)
        for k, cut in enumerate(m.cuts):
            w_a = pin.getFrameVelocity(model, data, cut.frame_a, pin.LOCAL_WORLD_ALIGNED).angular
            w_b = pin.getFrameVelocity(model, data, cut.frame_b, pin.LOCAL_WORLD_ALIGNED).angular
            axis = found[n_tree + k]
            relative = w_b - w_a
            assert np.linalg.norm(axis) == pytest.approx(1.0, abs=1e-12) and np.linalg.norm(relative) > 1e-3
            assert np.linalg.norm(relative - (relative @ axis) * axis) < 1e-10 * np.linalg.norm(relative)


def test_ball_joints_have_no_axis(load_cached):
    """The rocket gimbal's ball-joint cuts: NaN axes."""
    m = load_cached("rocket_gimbal")
    axes = _world_axes(m, _poses(m, (0.0,)))
    assert [c.closure.kind for c in m.cuts] == ["spherical", "spherical"]
    assert np.all(np.isnan(axes[:, m.model.njoints - 1 :]))
