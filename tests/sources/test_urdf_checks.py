"""`mechkit.sources.urdf_checks`: a tree or inertias that urdfdom lets through are named errors.

What the URDF format allows is accepted (massless links, point masses, thin rods, rotors: a moment
without mass), what no body can have is refused by name (negative mass, a negative principal moment,
the triangle inequality violated); the field's files agree.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from tests_support import SLIDER_CRANK, written

import mechkit
from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.urdf_checks import check_inertias

URDF_CASES = {
    "cycle in the tree": (
        SLIDER_CRANK.replace(
            '<parent link="ground"/><child link="crank_link"/>',
            '<parent link="slider_link"/><child link="crank_link"/>',
        ).replace(
            '<parent link="ground"/><child link="slider_link"/>', '<parent link="rod_link"/><child link="slider_link"/>'
        ),
        "cycle",
    ),
    "link with two parents": (
        SLIDER_CRANK.replace(
            '<parent link="ground"/><child link="slider_link"/>', '<parent link="ground"/><child link="rod_link"/>'
        ),
        "two parent joints",
    ),
    "negative mass": (SLIDER_CRANK.replace('<mass value="0.4"/>', '<mass value="-1"/>'), "mass -1"),
    "inertia not positive definite": (SLIDER_CRANK.replace('ixx="2e-5"', 'ixx="-2e-5"'), "positive semi-definite"),
}


@pytest.mark.parametrize("case", list(URDF_CASES))
def test_bad_urdf_is_a_named_error(case, tmp_path):
    text, needle = URDF_CASES[case]
    with pytest.raises(MalformedDescription, match=needle.replace("(", r"\(")):
        mechkit.load(written(tmp_path, text))


FIELD = Path(__file__).parent.parent / "fixtures" / "field"


def _link(mass: str, ixx="0", iyy="0", izz="0", ixy="0", ixz="0", iyz="0", rpy="0 0 0") -> ET.Element:
    return ET.fromstring(
        f'<robot name="r"><link name="body"><inertial><origin xyz="0 0 0" rpy="{rpy}"/>'
        f'<mass value="{mass}"/><inertia ixx="{ixx}" iyy="{iyy}" izz="{izz}" ixy="{ixy}" ixz="{ixz}" '
        f'iyz="{iyz}"/></inertial></link></robot>'
    )


def _rod(mass: float, length: float, radius: float) -> dict[str, str]:
    """A solid cylinder along x about its centre (kg m^2)."""
    axial = mass * radius**2 / 2
    transverse = mass * (3 * radius**2 + length**2) / 12
    return {"ixx": repr(axial), "iyy": repr(transverse), "izz": repr(transverse)}


@pytest.mark.parametrize(
    "mass, inertia",
    [
        ("0", {}),  # a massless link: a frame
        ("0.0", {"ixx": "0.0", "iyy": "-0.0"}),  # written with signed zeros
        ("1e-9", {}),  # a point mass (CAD exports' tool frames)
        ("2.5", _rod(2.5, 0.4, 0.0)),  # an ideal thin rod: one zero principal moment
        ("2.5", _rod(2.5, 0.4, 0.01)),  # a solid rod
        ("1.0", {"ixx": "0.5", "iyy": "0.5", "izz": "1.0"}),  # a flat disc: the triangle inequality with equality
        ("0", {"ixx": "1e-4", "iyy": "1e-4", "izz": "1.7e-4"}),  # a rotor: its inertia here, its mass counted elsewhere
    ],
)
def test_physically_possible_inertias_are_accepted(mass, inertia):
    check_inertias(_link(mass, **inertia))


def test_every_field_fixture_of_gepetto_passes_and_many_links_are_massless():
    """Gepetto's robots: 116 links of zero mass and many point masses, all physically possible."""
    massless = 0
    for urdf in sorted((FIELD / "gepetto").rglob("*.urdf")):
        root = ET.parse(urdf).getroot()
        check_inertias(root)
        massless += sum(1 for m in root.iter("mass") if float(m.get("value")) == 0.0)
    assert massless == 116


@pytest.mark.parametrize(
    "mass, inertia, needle",
    [
        ("-1", {"ixx": "1", "iyy": "1", "izz": "1"}, "mass -1 is negative"),
        ("-1e-12", {}, "mass -1e-12 is negative"),
        ("0", {"izz": "1e-3"}, "triangle inequality"),  # a rotor, but no body
        ("1", {"ixx": "-2e-5", "iyy": "1e-4", "izz": "1e-4"}, "not positive semi-definite"),
        ("1", {"ixx": "1", "iyy": "1", "izz": "1", "ixy": "2"}, "not positive semi-definite"),  # eigenvalue -1
        ("1", {"ixx": "0.05", "iyy": "0.03", "izz": "0.01"}, "triangle inequality"),  # 0.01 + 0.03 < 0.05
        ("1", {"izz": "4.5389e-05"}, "triangle inequality"),  # a planar model's izz alone
        ("1", {"ixx": "nan", "iyy": "1", "izz": "1"}, "is not finite"),
        ("one", {}, "mass 'one' is not a number"),
    ],
)
def test_physically_impossible_inertias_are_refused_by_name(mass, inertia, needle):
    with pytest.raises(MalformedDescription, match=needle) as err:
        check_inertias(_link(mass, **inertia))
    assert err.value.where == "link 'body'"


def test_the_triangle_inequality_is_judged_on_principal_moments_not_on_the_written_diagonal():
    """A box of sides 0.1, 0.2, 0.3 m rotated by rpy: its tensor in the link frame has products of
    inertia; the check accepts it, and refuses the same tensor once one principal moment is inflated."""
    m, a, b, c = 2.0, 0.1, 0.2, 0.3
    principal = np.diag([m * (b**2 + c**2), m * (a**2 + c**2), m * (a**2 + b**2)]) / 12
    R = pin.rpy.rpyToMatrix(0.3, -0.7, 1.1)
    for moments, ok in ((principal, True), (principal + np.diag([0, 0, 5 * principal[2, 2]]), False)):
        tensor = R @ moments @ R.T
        attrs = {
            k: repr(float(tensor[i, j]))
            for k, (i, j) in {
                "ixx": (0, 0),
                "iyy": (1, 1),
                "izz": (2, 2),
                "ixy": (0, 1),
                "ixz": (0, 2),
                "iyz": (1, 2),
            }.items()
        }
        if ok:
            check_inertias(_link(repr(m), **attrs))
        else:
            with pytest.raises(MalformedDescription, match="triangle inequality"):
                check_inertias(_link(repr(m), **attrs))


@pytest.mark.parametrize(
    "file, link, needle",
    [
        ("planar_leg_linkage.urdf", "thigh", "triangle inequality"),  # izz only: a planar model
        ("mini_cheetah_leg.urdf", "abduct", "triangle inequality"),
    ],
)
def test_the_urdf_plus_authors_files_that_no_body_can_have_are_refused_by_name(file, link, needle):
    """generalized_rbda's example models (URDF+'s authors) write planar bodies with izz alone: no body has
    that inertia (MuJoCo refuses it too)."""
    with pytest.raises(MalformedDescription, match=needle) as err:
        check_inertias(ET.parse(FIELD / "urdf_plus" / file).getroot())
    assert err.value.where == f"link {link!r}"


@pytest.mark.parametrize("file, rotors", [("revolute_rotor_chain.urdf", 3), ("mit_humanoid_leg.urdf", 5)])
def test_the_urdf_plus_authors_rotors_are_accepted(file, rotors):
    """Their rotors have an inertia and no mass (the mass counted in the link): accepted, as the URDF
    allows; Pinocchio gives those bodies their rotational inertia and no weight."""
    root = ET.parse(FIELD / "urdf_plus" / file).getroot()
    check_inertias(root)
    massless = [
        link.get("name")
        for link in root.iter("link")
        if link.find("inertial") is not None and float(link.find("inertial/mass").get("value")) == 0.0
    ]
    assert len(massless) == rotors
