"""Sections and joint elasticity: the tube's constants, checks at the boundary, scaling."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.elastic import ElasticData, JointElasticity, Section


def test_tube_constants():
    s = Section.tube(0.020, 0.016, 70e9, 26e9, (0, -2, 0), density=2700)
    assert math.isclose(s.A, math.pi * (0.02**2 - 0.016**2) / 4)
    assert math.isclose(s.I1, math.pi * (0.02**4 - 0.016**4) / 64) and s.I1 == s.I2 and math.isclose(s.J, 2 * s.I1)
    assert np.allclose(s.axis1, [0, -1, 0]) and math.isclose(s.mass(2.0), 2700 * s.A * 2.0)


@pytest.mark.parametrize("bad", [{"E": 0.0}, {"A": -1.0}, {"J": float("nan")}, {"axis1": (0, 0, 0)}])
def test_bad_sections_are_refused(bad):
    values = {"E": 1.0, "G": 1.0, "A": 1.0, "I1": 1.0, "I2": 1.0, "J": 1.0} | bad
    with pytest.raises(InvalidParameters):
        Section(**values)


def test_joint_elasticity_and_scaling():
    with pytest.raises(InvalidParameters):
        JointElasticity(stiffness=[1, 2, 3])
    with pytest.raises(InvalidParameters):
        JointElasticity(drive=-1.0)
    data = (
        ElasticData()
        .with_section("a", Section.tube(0.02, 0.0, 1e9, 4e8))
        .with_joint("j", JointElasticity(0.1, np.ones(6), 5.0))
    )
    scaled = data.scaled(10.0)
    assert scaled.sections["a"].E == 1e10 and scaled.joints["j"].drive == 50.0 and scaled.joints["j"].centre == 0.1
    assert not ElasticData() and data.with_section("a", None).sections == {}
