"""`mechkit.loading`: names, parameters, paths and URDF text refused by name."""

from __future__ import annotations

import pytest
from tests_support import SLIDER_CRANK, written

import mechkit
from mechkit.base.exceptions import (
    ClosureNotConverged,
    IgnoredClosure,
    InvalidArgument,
    InvalidParameters,
    MalformedDescription,
    MechkitError,
)

NAME = "five_bar"


LOAD_CASES = {
    "name-none": ((None,), {}, InvalidArgument),
    "name-number": ((123,), {}, InvalidArgument),
    "name-unknown": (("nope",), {}, InvalidParameters),
    "param-unknown": ((NAME,), {"bogus": 1.0}, InvalidParameters),
    "param-nan": ((NAME,), {"prox1": float("nan")}, InvalidParameters),
    "param-inf": ((NAME,), {"prox1": float("inf")}, InvalidParameters),
    "param-negative-length": ((NAME,), {"prox1": -0.1}, InvalidParameters),
    "param-zero-density": ((NAME,), {"density": 0.0}, InvalidParameters),
    "param-string": ((NAME,), {"prox1": "long"}, InvalidParameters),
    "density-below-pinocchio-epsilon": ((NAME,), {"density": 1e-12}, InvalidParameters),
    "cannot-assemble": ((NAME,), {"dist1": 0.01, "dist2": 0.01}, (ClosureNotConverged, InvalidParameters)),
    "actuated-unknown": ((NAME,), {"actuated": ["nope"]}, MechkitError),
}


@pytest.mark.parametrize("case", list(LOAD_CASES))
def test_load_refuses_bad_names_and_parameters(case):
    args, kwargs, kind = LOAD_CASES[case]
    with pytest.raises(kind):
        mechkit.load(*args, **kwargs)


@pytest.mark.parametrize(
    "urdf,kind",
    [
        (None, InvalidArgument),
        ("", InvalidArgument),
        (42, InvalidArgument),
        ("<robot name='x'><link name='a'/>", MalformedDescription),
        ("/no/such/file.urdf", MalformedDescription),
    ],
)
def test_from_urdf_refuses_what_is_not_urdf(urdf, kind):
    with pytest.raises(kind):
        mechkit.from_urdf(urdf)


def test_paths_that_are_not_files(tmp_path):
    with pytest.raises(MalformedDescription, match="no such file"):
        mechkit.load(tmp_path / "missing.urdf")
    with pytest.raises(MalformedDescription, match="directory"):
        mechkit.load(tmp_path)
    with pytest.raises(MalformedDescription, match="unknown format"):
        mechkit.load(written(tmp_path, SLIDER_CRANK, "linkage.txt"))
    with pytest.raises(InvalidParameters, match="no such mechanism"):
        mechkit.load("slider_crank")


CLOSURE_FILES = ("four_bar_drake_distance.sdf",)  # the others are read (tests/sources/test_drake_elements.py)


@pytest.mark.parametrize("name", CLOSURE_FILES)
def test_another_tool_s_closure_is_refused_by_name_never_an_open_tree(name):
    """A four-bar closed by Drake's or Gazebo's element loads as nothing, not as a 3-DOF open tree."""
    from tests_support import FIXTURES

    with pytest.raises(MalformedDescription, match=rf"^{name}:\d+: <(drake:|gazebo/)"):
        mechkit.load(FIXTURES / "closures" / name)


@pytest.mark.parametrize("name", CLOSURE_FILES)
def test_asked_to_ignore_it_the_tree_loads_with_one_warning_naming_the_mobility_left(name):
    from tests_support import FIXTURES

    with pytest.warns(IgnoredClosure) as caught:
        m = mechkit.load(FIXTURES / "closures" / name, ignore_unknown_closures=True)
    assert m.home_mobility.dof == 3 and len(caught) == 1
    assert f"{name}:" in str(caught[0].message) and "left with 3 degree(s) of freedom" in str(caught[0].message)


def test_the_option_to_ignore_is_a_flag():
    with pytest.raises(InvalidArgument, match="ignore_unknown_closures"):
        mechkit.load("four_bar", ignore_unknown_closures="yes")


def test_load_puts_the_mechanism_on_a_base():
    """`base=` gives the mechanism `mechkit.bases.with_base` gives, on top of locked joints too."""
    from mechkit.bases import BASE_JOINTS, FLOATING_JOINT

    floating = mechkit.load("four_bar", base="floating", base_inertia=(5.0, (0.1, 0.1, 0.1)), gravity=(0, 0, 0))
    assert floating.model.names[1] == FLOATING_JOINT and not floating.model.gravity.linear.any()
    moving = mechkit.load("spherical_2dof", base="moving", lock={"r21": 0.9})
    assert moving.actuated[:6] == BASE_JOINTS and "r21" not in moving.model.names
    with pytest.raises(InvalidArgument, match="base"):
        mechkit.load("four_bar", base="rolling")
