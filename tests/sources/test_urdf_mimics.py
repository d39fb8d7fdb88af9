"""`mechkit.sources.urdf_mimics`: a chain of `<mimic>` joints read as coupling rows, and the rows obeyed by
the assembled mechanism's configuration and velocities (the single mimics, their defaults and every
malformed mimic: tests/sources/test_urdf.py)."""

from __future__ import annotations

import numpy as np
import pytest

import mechkit
from mechkit.base.exceptions import MalformedDescription
from mechkit.core import Coupling
from mechkit.sources.urdf import parse_xml
from mechkit.sources.urdf_mimics import parse_mimics

INERTIAL = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'


def _chain(mimic3: str = '<mimic joint="j2" multiplier="0.5"/>') -> str:
    """Three sliders on a base: j2 mimics j1 (-2, offset 0.01), j3 carries `mimic3`."""
    joints = "".join(
        f'<link name="l{k}">{INERTIAL}</link><joint name="j{k}" type="prismatic"><parent link="base"/>'
        f'<child link="l{k}"/><axis xyz="0 {k} 1"/><limit effort="10" lower="-1" upper="1" velocity="1"/>'
        f"{mimic}</joint>"
        for k, mimic in ((1, ""), (2, '<mimic joint="j1" multiplier="-2" offset="0.01"/>'), (3, mimic3))
    )
    return f'<robot name="chain"><link name="base"/>{joints}</robot>'


def test_a_chain_of_mimics_is_one_row_each_and_the_mechanism_obeys_both():
    assert parse_mimics(parse_xml(_chain())) == (
        Coupling("j2", (("j2", 1.0),), (("j1", 1.0),), (0.01, -2.0)),
        Coupling("j3", (("j3", 1.0),), (("j2", 1.0),), (0.0, 0.5)),
    )
    m = mechkit.from_urdf(_chain(), actuated=["j1"])
    assert m.mobility().dof == 1
    q = m.assemble({"j1": 0.3})
    x = {j: q[m.q_index(j)] for j in ("j1", "j2", "j3")}
    assert x["j2"] == pytest.approx(-2 * x["j1"] + 0.01, abs=1e-12)
    assert x["j3"] == pytest.approx(0.5 * x["j2"], abs=1e-12)
    v = m.velocities(q, [0.7])
    np.testing.assert_allclose([v[m.v_index(j)] for j in ("j1", "j2", "j3")], [0.7, -1.4, -0.7], rtol=0, atol=1e-12)


def test_a_mimic_closing_the_chain_is_a_cycle_named_joint_by_joint():
    with pytest.raises(MalformedDescription, match="cycle") as err:
        parse_mimics(
            parse_xml(
                _chain().replace(
                    '<limit effort="10" lower="-1" upper="1" velocity="1"/></joint>',
                    '<limit effort="10" lower="-1" upper="1" velocity="1"/><mimic joint="j3"/></joint>',
                    1,
                )
            )
        )
    assert all(j in str(err.value) for j in ("j1", "j2", "j3"))
