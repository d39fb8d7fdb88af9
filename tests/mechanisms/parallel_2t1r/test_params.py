"""`mechkit.mechanisms.parallel_2t1r.params`: the URDF's inertias are the validators' inertias."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest

from mechkit.mechanisms.parallel_2t1r import SPEC
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams, mass_properties
from mechkit.sources.xacro_file import render_urdf


def test_urdf_inertias_are_the_validators_inertias():
    p = Parallel2T1RParams(payload_mass=3.0, bar_width=0.03)
    root = ET.fromstring(render_urdf(SPEC.template_path, p.xacro_args()))
    for name, (mass, com, inertia) in mass_properties(p).items():
        inertial = root.find(f"link[@name='{name}']/inertial")
        assert float(inertial.find("mass").get("value")) == pytest.approx(mass, rel=1e-14)
        np.testing.assert_allclose([float(x) for x in inertial.find("origin").get("xyz").split()], com, atol=1e-15)
        tensor = inertial.find("inertia")
        np.testing.assert_allclose([float(tensor.get(k)) for k in ("ixx", "iyy", "izz")], np.diag(inertia), rtol=1e-14)
