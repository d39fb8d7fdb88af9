"""Closure records (`mechkit.core.records`): plain frozen data, resolved on a model by `mechkit.core.cuts` and
`mechkit.core.coupling_rows`."""

from __future__ import annotations

import dataclasses

import pytest

from mechkit import core
from mechkit.base.exceptions import InvalidParameters
from mechkit.core import JointSpring


def test_records_are_frozen_and_carry_their_defaults():
    c = core.Coupling("gear", (("a", 1.0),), (("b", 2.0),))
    assert c.polynomial == (0.0, 1.0) and c.follower_ref == c.leader_ref == 0.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        c.name = "other"  # type: ignore[misc]
    assert core.JointSpring("j").stiffness == 0.0
    assert core.LoopClosure("C", "spherical", "a", "b").rows == "spatial"
    assert core.LOOP_KINDS == ("revolute", "prismatic", "spherical", "hooke", "weld")


@pytest.mark.parametrize(
    "values, named",
    [
        ({"stiffness": -1.0}, "spring stiffness of 'crank'"),
        ({"damping": -0.5}, "spring damping of 'crank'"),
        ({"stiffness": float("inf")}, "spring stiffness of 'crank'"),
        ({"reference": float("nan")}, "spring reference of 'crank'"),
        ({"preload": float("inf")}, "spring preload of 'crank'"),
    ],
)
def test_a_spring_no_spring_can_be_is_refused_naming_the_joint(values, named):
    """A negative stiffness was accepted (an energy source presented as a spring)."""
    with pytest.raises(InvalidParameters, match=named):
        JointSpring("crank", **values)
