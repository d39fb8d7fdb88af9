"""The compliant SOC second opinion (unit-load method) agrees with the force method of `ElasticModel`."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit.base.exceptions import MethodUnavailable
from mechkit.elastic import ElasticModel, JointElasticity
from mechkit.elastic.unit_load import UnitLoad

TOL = 1e-6


def _agree(e: ElasticModel, unit: UnitLoad, q: np.ndarray) -> float:
    v = np.zeros(e.mech.model.nv)
    r = e.inverse_dynamics(q, v, v)
    u = unit.reactions(q, v, v)
    return (
        max(np.abs(r.reactions[0, k] - u[name]).max() for k, name in enumerate(r.joint_names))
        / np.abs(r.reactions).max()
    )


def test_four_bar_under_tilted_gravity():
    """Gravity with a component along the axes loads the out-of-plane components rigid statics leaves open."""
    m = mechkit.load("four_bar", rows="spatial")
    m.model.gravity = pin.Motion(np.array([0.0, -4.0, -9.0]), np.zeros(3))
    e = ElasticModel(m)
    assert not m.inverse_dynamics(m.home_q, np.zeros(3), np.zeros(3)).determinate.all()
    assert _agree(e, UnitLoad(m), m.home_q) < TOL
    drive = JointElasticity(drive=500.0)
    assert _agree(e.with_joint("crank", drive), UnitLoad(m, e.data.with_joint("crank", drive)), m.home_q) < TOL


@pytest.mark.parametrize("name", ["parallel_2t1r", "spherical_2dof", "deployable_9rr12uru"])
def test_redundant_mechanisms(name):
    """The 2T1R's limb III, the spherical platform's limbs, the deployable's redundant chain: the two
    force methods agree where the frame model's round-off does not reach (see docs/elastic.md)."""
    m = mechkit.load(name)
    assert _agree(ElasticModel(m), UnitLoad(m), m.home_q) < TOL


def test_joint_stiffness_is_not_covered():
    m = mechkit.load("four_bar")
    data = ElasticModel(m).data.with_joint("C", JointElasticity(stiffness=np.full(6, 1e6)))
    with pytest.raises(MethodUnavailable):
        UnitLoad(m, data)
