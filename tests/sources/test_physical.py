"""`mechkit.sources.physical`: bodies and geometry judged on the model every format ends in; what a reader
let through (a negative mass in SDFormat, a non-finite axis MuJoCo compiled to NaN) is refused by name, and
what is physical but degenerate (massless frames, point masses, thin rods, rotors) passes."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from tests_support import FIXTURES

import mechkit
from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.physical import check_body, check_model

SDF = FIXTURES / "field" / "sdf" / "four_bar_gearbox.sdf"


@pytest.mark.parametrize(
    "mass, moments",
    [(0.0, (0, 0, 0)), (1.0, (0, 0, 0)), (1.0, (0, 1, 1)), (0.0, (1e-4, 1e-4, 2e-4)), (2.0, (1, 2, 3))],
)
def test_degenerate_but_physical_bodies_pass(mass, moments):
    check_body("link 'x'", mass, np.diag(moments).astype(float), moments)


@pytest.mark.parametrize(
    "mass, inertia, why",
    [
        (-1.0, np.eye(3), "mass -1 is negative or not finite"),
        (np.nan, np.eye(3), "mass nan is negative or not finite"),
        (1.0, np.diag([1.0, 1.0, np.inf]), "not finite"),
        (1.0, np.diag([-1e-3, 1.0, 1.0]), "not positive semi-definite"),
        (1.0, np.diag([1.0, 1.0, 3.0]), "violates the triangle inequality"),
        (1.0, np.array([[1.0, 0.9, 0], [0.9, 1.0, 0], [0, 0, 0.5]]), "triangle"),  # moments 0.1, 0.5, 1.9
    ],
)
def test_impossible_bodies_are_refused_by_name(mass, inertia, why):
    with pytest.raises(MalformedDescription, match=why) as err:
        check_body("link 'x'", mass, inertia, "given")
    assert str(err.value).startswith("link 'x': ")


def test_a_negative_mass_in_sdformat_is_refused_not_held_by_a_1e12_motor(tmp_path):
    path = tmp_path / "negative.sdf"
    path.write_text(SDF.read_text().replace("<mass>0.12</mass>", "<mass>-0.12</mass>"))
    with pytest.raises(MalformedDescription, match=r"link 'coupler': mass -0.12 is negative"):
        mechkit.load(path)


def test_non_finite_geometry_is_refused_by_name():
    model = pin.buildSampleModelManipulator()
    check_model(model)
    bad = model.copy()
    bad.jointPlacements[2] = pin.SE3(np.eye(3), np.array([np.nan, 0, 0]))
    with pytest.raises(MalformedDescription, match=rf"joint {model.names[2]!r}: its placement is not finite"):
        check_model(bad)
    bad = model.copy()
    bad.gravity = pin.Motion(np.array([0, 0, np.inf, 0, 0, 0]))
    with pytest.raises(MalformedDescription, match="gravity"):
        check_model(bad)


def test_an_mjcf_axis_of_inf_is_refused_not_a_linalg_traceback(tmp_path):
    """MuJoCo compiles `axis="0 0 inf"` into NaN placements; the SVD of the assembly then failed."""
    text = (FIXTURES / "rssr.xml").read_text()
    path = tmp_path / "inf_axis.xml"
    path.write_text(
        text.replace(
            '<joint name="crank" type="hinge" axis="0 0 1"/>', '<joint name="crank" type="hinge" axis="0 0 inf"/>'
        )
    )
    assert path.read_text() != text
    with pytest.raises(MalformedDescription, match="not finite"):
        mechkit.load(path)


@pytest.mark.parametrize("axis", ["0 -1e-300 0", "0 1e-170 0", "0 0 0"])
def test_a_joint_axis_of_no_length_is_refused_by_name(tmp_path, axis):
    """The URDF parser leaves an axis whose squared length underflows unnormalised (its column 1e-300 long):
    refused by the joint's name, where the determinacy's inverse once overflowed."""
    text = (
        '<robot name="r"><link name="a"/><link name="b"><inertial><mass value="1"/><inertia ixx="1" iyy="1" '
        'izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link><joint name="j" type="revolute"><parent link="a"/>'
        f'<child link="b"/><axis xyz="{axis}"/><limit effort="1" lower="-1" upper="1" velocity="1"/></joint></robot>'
    )
    path = tmp_path / "axis.urdf"
    path.write_text(text)
    with pytest.raises(MalformedDescription, match="joint 'j'.*axis is not a direction"):
        mechkit.load(path)
    path.write_text(text.replace(f'xyz="{axis}"', 'xyz="0 2 0"'))  # a long axis is normalised: loads
    assert mechkit.load(path).model.nv == 1
