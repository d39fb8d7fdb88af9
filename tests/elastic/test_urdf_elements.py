"""The elastic elements of a URDF: the built-ins carry them, the rigid pipeline ignores them, and they
read back what was written."""

from __future__ import annotations

import numpy as np
import pytest

import mechkit
from mechkit.base.exceptions import MalformedDescription
from mechkit.base.resources import urdf_dir
from mechkit.elastic import parse_elastic, with_elastic


def test_the_reference_sections_of_the_issue():
    four = parse_elastic((urdf_dir() / "four_bar.urdf").read_text())
    assert set(four.sections) == {"crank_link", "coupler_link", "rocker_link"}
    s = four.sections["coupler_link"]
    assert (s.E, s.G) == (70e9, 26e9) and np.isclose(s.A, np.pi * (0.02**2 - 0.016**2) / 4)
    t = parse_elastic((urdf_dir() / "parallel_2t1r.urdf").read_text())
    assert "link22" not in t.sections and len(t.sections) == 7 and t.sections["link41"].E == 210e9
    assert np.isclose(t.sections["link41"].I1, np.pi * (0.03**4 - 0.024**4) / 64)


def test_the_rigid_pipeline_ignores_the_elements(tmp_path):
    """Removing every elastic element changes no rigid result."""
    m = mechkit.load("spherical_2dof")
    bare = tmp_path / "bare.urdf"
    bare.write_text(with_elastic(m.urdf, parse_elastic("<robot name='x'/>")))
    assert "beam" not in bare.read_text() and "beam" in m.urdf
    other = mechkit.load(bare, actuated=list(m.actuated))
    v = np.zeros(m.model.nv)
    q = m.assemble([0.1, -0.1])
    assert np.array_equal(m.inverse_dynamics(q, v, v).reaction_values, other.inverse_dynamics(q, v, v).reaction_values)


def test_round_trip_and_errors():
    urdf = (urdf_dir() / "spherical_2dof.urdf").read_text()
    data = parse_elastic(urdf)
    assert data.joints["r13"].centre == pytest.approx(0.12)
    again = parse_elastic(with_elastic(urdf, data))
    assert again.sections.keys() == data.sections.keys() and again.joints.keys() == data.joints.keys()
    assert np.allclose(again.sections["link11"].axis1, data.sections["link11"].axis1)
    bad = urdf.replace('density="2700.0" link="link11"', 'density="2700.0" link="no_such_link"', 1)
    with pytest.raises(MalformedDescription, match="not a link"):
        parse_elastic(bad)
    with pytest.raises(MalformedDescription, match="bad or missing"):
        parse_elastic(urdf.replace(' E="70000000000.0"', "", 1))
