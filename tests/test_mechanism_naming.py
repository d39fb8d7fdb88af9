"""`mechkit.mechanism_naming.JointNaming`, built from a closure model alone (no `Mechanism` around it):
indices that locate each joint's value and velocity (checked by Pinocchio's integration), values by name
or in input order landing in their joints' velocity slots, one sample or N, transmission names standing
for the joints they drive only where the URDF says so, and bad arguments refused by name."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from tests_support import FIXTURES

import mechkit
from mechkit.base.exceptions import InvalidArgument, InvalidParameters
from mechkit.mechanism_naming import JointNaming

FOUR_BAR = Path(mechkit.__file__).parent / "urdf" / "four_bar.urdf"


@pytest.fixture(scope="module")
def leg():
    """The leg fixture: revolute joints and two ball joints (nq 4, nv 3), named apart from any Mechanism."""
    return JointNaming("leg", mechkit.load(FIXTURES / "leg.urdf").closure_model)


def test_the_indices_locate_each_joints_value_and_velocity(leg):
    """A step along a joint's velocity slots (from v_index) moves that joint alone, and a 1-dof joint's
    value is q at its q_index."""
    model = leg.model
    q = pin.randomConfiguration(model, -np.ones(model.nq), np.ones(model.nq))
    before = leg.joint_values(q)
    for joint in model.names[1:]:
        width = model.joints[leg.joint_id(joint)].nv
        step = np.zeros(model.nv)
        step[leg.v_index(joint) : leg.v_index(joint) + width] = 0.1
        after = leg.joint_values(pin.integrate(model, q, step))
        moved = [j for j in before if not np.allclose(after[j], before[j], rtol=0, atol=1e-12)]
        assert moved == [joint]
        if width == 1:
            assert q[leg.q_index(joint)] == before[joint]


def test_values_by_name_or_in_order_land_in_their_joints_velocity_slots(leg):
    """A revolute and a ball joint's (3,) value, by name in any order or in the order of the inputs, one
    sample or two: each value lands in its own joint's velocity slots."""
    ball = leg.v_index("rod1_top_z")
    for values, names in (
        ({"rod1_top_z": [0.1, 0.2, 0.3], "hip": 0.3}, ()),
        ([0.3, 0.1, 0.2, 0.3], ["hip", "rod1_top_z"]),
    ):
        split, x = leg.given(values, names, "input_rates")
        v = np.zeros(leg.model.nv)
        v[split.input_v] = x
        assert v[leg.v_index("hip")] == 0.3 and list(v[ball : ball + 3]) == [0.1, 0.2, 0.3]
        assert np.count_nonzero(v) == 4
    rows = {"hip": np.array([0.3, -0.4]), "rod1_top_z": np.array([[0.1, 0.2, 0.3], [0.4, 0.5, 0.6]])}
    split, X = leg.given_batch(rows, ("hip", "rod1_top_z"), 2, "input_rates")
    for k in range(2):
        one_split, x = leg.given({j: r[k] for j, r in rows.items()}, (), "input_rates")
        assert one_split.names == split.names and np.array_equal(X[k], x)


def test_a_transmission_names_its_joint_where_the_urdf_says_so():
    model = mechkit.load(FOUR_BAR).closure_model
    named = JointNaming("four_bar", model, FOUR_BAR.read_text())
    assert named.aliases == {"crank_transmission": "crank"}
    assert named.values({"crank_transmission": 0.5}, (), "inputs") == {"crank": 0.5}
    assert named.input_joints(named.input_names(["crank_transmission"], "rates")) == ["crank"]
    with pytest.raises(InvalidArgument, match="'inputs'.*crank_transmission"):
        JointNaming("four_bar", model).values({"crank_transmission": 0.5}, (), "inputs")


def test_bad_arguments_are_refused_by_name(leg):
    with pytest.raises(InvalidArgument, match="'q'"):
        leg.one(q=np.zeros(leg.model.nq + 1))
    with pytest.raises(InvalidArgument, match="'q, v'"):
        leg.many(q=np.zeros((2, leg.model.nq)), v=np.zeros((3, leg.model.nv)))
    with pytest.raises(InvalidParameters, match="no such joint|nope"):
        leg.joint_id("nope")
    unactuated = JointNaming("bare", mechkit.load(FOUR_BAR, actuated=[]).closure_model)
    with pytest.raises(InvalidParameters, match="bare is unactuated.*velocities"):
        unactuated.input_names(None, "velocities")
    with pytest.raises(InvalidParameters, match="'actuated'"):
        unactuated.values([0.5], (), "inputs")
