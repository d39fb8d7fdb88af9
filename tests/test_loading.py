"""`mechkit.loading`: names, parameters, paths and URDF text refused by name."""

from __future__ import annotations

import pytest
from tests_support import SLIDER_CRANK, written

import mechkit
from mechkit.base.exceptions import (
    ClosureNotConverged,
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
