"""A base for every mechanism: the moving base's invariances (Galilean, equivalent gravity, a tilted
carrier), the carrier's wrench from Newton's law, the floating base's bus, and the refusals."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit.base.exceptions import InvalidArgument
from mechkit.bases.carrier import BASE_JOINTS, CARRIER_JOINT, FLOATING_JOINT, base_of, with_base

G = np.array([0.0, 0.0, -9.81])


@pytest.fixture(scope="module")
def fixed(load_cached):
    return load_cached("spherical_2dof")


@pytest.fixture(scope="module")
def moving(fixed):
    return with_base(fixed, "moving", base_inertia=(2.0, (0.1, 0.2, 0.25)))


@pytest.fixture(scope="module")
def state(fixed):
    """A moving state of the platform: its home with input rates and accelerations."""
    q = fixed.home_q
    v = fixed.velocities(q, {"r11": 0.7, "r21": -0.4})
    return q, v, fixed.accelerations(q, v, {"r11": -1.3, "r21": 2.1})


def _on_base(moving, state, qb, vb, ab):
    q, v, a = state
    return moving.inverse_dynamics(np.r_[qb, q], np.r_[vb, v], np.r_[ab, a])


def _scale(result):
    return max(np.abs(result.effort_values).max(), np.abs(result.reaction_values).max())


def test_galilean_invariance(fixed, moving, state):
    """A base moving at a constant velocity, anywhere, gives the fixed base's efforts and reactions."""
    ref = fixed.inverse_dynamics(*state)
    out = _on_base(moving, state, [0.3, -0.2, 0.5, 0, 0, 0], [1.5, -0.7, 0.4, 0, 0, 0], np.zeros(6))
    assert out.joint_names[6:] == ref.joint_names
    assert np.abs(out.effort_values[6:] - ref.effort_values).max() < 1e-12 * _scale(ref)
    assert np.abs(out.reaction_values[6:] - ref.reaction_values).max() < 1e-12 * _scale(ref)


def test_uniform_acceleration_is_gravity(fixed, moving, state):
    """A base accelerating uniformly at a0 gives the efforts of a fixed base under gravity g - a0."""
    a0 = np.array([2.0, -1.0, 5.0])
    out = _on_base(moving, state, np.zeros(6), [0.5, 0, 0, 0, 0, 0], np.r_[a0, 0, 0, 0])
    ref = with_base(fixed, "fixed", gravity=G - a0).inverse_dynamics(*state)
    assert np.abs(out.effort_values[6:] - ref.effort_values).max() < 1e-12 * _scale(ref)
    assert np.abs(out.reaction_values[6:] - ref.reaction_values).max() < 1e-12 * _scale(ref)


def test_tilted_carrier_is_rotated_gravity(fixed, moving, state):
    """A still carrier at roll, pitch, yaw gives the efforts of a fixed base under gravity R^T g."""
    yaw, pitch, roll = 0.3, -0.15, 0.2
    rotation = pin.rpy.rpyToMatrix(roll, pitch, yaw)
    out = _on_base(moving, state, [0.1, 0.2, 0.3, yaw, pitch, roll], np.zeros(6), np.zeros(6))
    ref = with_base(fixed, "fixed", gravity=rotation.T @ G).inverse_dynamics(*state)
    assert np.abs(out.effort_values[6:] - ref.effort_values).max() < 1e-10 * _scale(ref)
    # the reactions are in world axes: the carried ones rotated back into the carrier's
    carried = out.reaction_values[6:].reshape(-1, 2, 3) @ rotation
    assert np.abs(carried.reshape(-1, 6) - ref.reaction_values).max() < 1e-10 * _scale(ref)


def test_carrier_wrench_holds_the_weight(fixed, moving):
    """At rest on a tilted carrier, the carrier's wrench on the ground body is the whole weight, through
    the centre of mass (Newton and Euler for the carried system)."""
    qb = np.array([0.1, -0.2, 0.3, 0.4, 0.1, -0.25])
    q = np.r_[qb, fixed.home_q]
    out = moving.inverse_dynamics(q, np.zeros(moving.model.nv), np.zeros(moving.model.nv))
    reaction = out.reaction_values[list(out.joint_names).index(CARRIER_JOINT)]
    data = moving.model.createData()
    mass = pin.computeTotalMass(moving.model)
    com = pin.centerOfMass(moving.model, data, q)
    origin = qb[:3]  # the carrier joint's origin is the ground body's, wherever the carrier turns it
    assert mass == pytest.approx(pin.computeTotalMass(fixed.model) + 2.0, rel=1e-14)
    np.testing.assert_allclose(reaction[:3], -mass * G, atol=1e-12 * mass * 9.81)
    np.testing.assert_allclose(reaction[3:], np.cross(com - origin, -mass * G), atol=1e-12 * mass * 9.81)


def test_floating_base(fixed):
    """A floating base: a free-flyer root carrying the bus's inertia, gravity as given."""
    floating = with_base(fixed, "floating", base_inertia=(40.0, (3.0, 4.0, 5.0)), gravity=(0, 0, 0))
    assert base_of(floating) == "floating" and base_of(fixed) == "fixed"
    j = floating.model.getJointId(FLOATING_JOINT)
    assert floating.model.nvs[j] == 6 and floating.model.inertias[j].mass == pytest.approx(40.0)
    assert np.all(floating.model.gravity.linear == 0)
    assert floating.home_mobility.dof == fixed.home_mobility.dof + 6
    np.testing.assert_allclose(floating.home_q[7:], fixed.home_q, atol=1e-12)


def test_moving_base_has_six_driven_roots(fixed, moving):
    assert base_of(moving) == "moving"
    assert moving.actuated[:6] == BASE_JOINTS and moving.actuated[6:] == fixed.actuated
    assert with_base(fixed, "fixed") is fixed


@pytest.mark.parametrize(
    ("kwargs", "arg"),
    [
        ({"base": "orbiting"}, "base"),
        ({"base": "fixed", "base_inertia": (1.0, (1, 1, 1))}, "base_inertia"),
        ({"base": "floating"}, "base_inertia"),
        ({"base": "floating", "base_inertia": (1.0, (1, 1, 5))}, "base_inertia"),
        ({"base": "floating", "base_inertia": (-1.0, (1, 1, 1))}, "base_inertia"),
        ({"base": "moving", "gravity": (0, np.nan, 0)}, "gravity"),
    ],
)
def test_refusals_name_the_argument(fixed, kwargs, arg):
    with pytest.raises(InvalidArgument, match=arg):
        with_base(fixed, **kwargs)


def test_soc_second_opinion_agrees_on_a_moving_base(moving):
    """The automatic SOC virtual-work solve (an independent method) against constrained RNEA, on a carrier
    that translates, turns and accelerates in every direction: efforts and every determinate reaction."""
    from mechkit.second_opinion.agreement import agreement
    from mechkit.second_opinion.opinion import SecondOpinion

    rng = np.random.default_rng(1)
    names, states = list(moving.actuated), []
    for k in range(3):
        base = dict(zip(BASE_JOINTS, rng.normal(0.0, 0.2, 6)))
        q = moving.assembly({**base, "r11": 0.9 + 0.05 * k, "r21": 1.0}).q
        v = moving.velocities(q, np.r_[rng.normal(0.0, 0.5, 6), 0.3, -0.2], names)
        states.append((q, v, moving.accelerations(q, v, np.r_[rng.normal(0.0, 1.0, 6), 0.5, 0.4], names)))
    result = agreement(SecondOpinion(moving), states, timing=False)
    assert result.determinacy_mismatches == []
    assert result.max_relative_difference < 1e-10
    assert "effort base_roll" in result.by_quantity  # the carrier's wrench is compared too


def test_scenes_carry_over_with_the_base_at_home(fixed, moving):
    """The cone scene's poses on the moving base: the base's six coordinates at 0, the loops closed."""
    poses = moving.spec.scenes["cone"](moving)
    assert len(poses) == len(fixed.spec.scenes["cone"](fixed))
    for q in poses[::12]:
        assert q.shape == (moving.model.nq,) and not q[:6].any()
        assert np.abs(moving.closure_residual(q)).max() < 1e-10
