"""Closure records (`mechkit.core.records`): plain frozen data, resolved on a model by `mechkit.core.cuts`."""

from __future__ import annotations

import dataclasses

import numpy as np
import pinocchio as pin
import pytest

from mechkit import core
from mechkit.base.exceptions import MalformedDescription
from mechkit.core.cuts import coupling_row


def test_records_are_frozen_and_carry_their_defaults():
    c = core.Coupling("gear", (("a", 1.0),), (("b", 2.0),))
    assert c.polynomial == (0.0, 1.0) and c.follower_ref == c.leader_ref == 0.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        c.name = "other"  # type: ignore[misc]
    assert core.JointSpring("j").stiffness == 0.0
    assert core.LoopClosure("C", "spherical", "a", "b").rows == "spatial"
    assert core.LOOP_KINDS == ("revolute", "prismatic", "spherical", "hooke", "weld")


def _two_joints():
    model = pin.Model()
    a = model.addJoint(0, pin.JointModelRZ(), pin.SE3.Identity(), "a")
    model.addJoint(a, pin.JointModelRUBZ(), pin.SE3.Identity(), "b")
    model.addJoint(0, pin.JointModelSpherical(), pin.SE3.Identity(), "ball")
    return model


def test_a_coupling_resolves_on_one_freedom_joints_only():
    model = _two_joints()
    row = coupling_row(model, core.Coupling("gear", (("a", 1.0),), (("b", -2.0),), (0.1, 1.0)))
    np.testing.assert_array_equal(row.unbounded, [False, True])  # b is continuous: its value is an angle
    np.testing.assert_array_equal(row.follower, [1.0, 0.0])
    np.testing.assert_array_equal(row.leader, [0.0, -2.0])
    for bad, words in (
        (core.Coupling("x", (("nope", 1.0),)), "not in the model"),
        (core.Coupling("x", (("ball", 1.0),)), "3 freedoms"),
        (core.Coupling("x", ()), "no follower"),
        (core.Coupling("x", (("a", 1.0),), polynomial=(np.nan,)), "finite"),
    ):
        with pytest.raises(MalformedDescription, match=words):
            coupling_row(model, bad)
