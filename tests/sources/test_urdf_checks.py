"""`mechkit.sources.urdf_checks`: a tree or inertias that urdfdom lets through are named errors."""

from __future__ import annotations

import pytest
from tests_support import SLIDER_CRANK, written

import mechkit
from mechkit.base.exceptions import MalformedDescription

URDF_CASES = {
    "cycle in the tree": (SLIDER_CRANK.replace('<parent link="ground"/><child link="crank_link"/>',
                                         '<parent link="slider_link"/><child link="crank_link"/>')
                          .replace('<parent link="ground"/><child link="slider_link"/>', '<parent link="rod_link"/><child link="slider_link"/>'),
                          "cycle"),
    "link with two parents": (SLIDER_CRANK.replace('<parent link="ground"/><child link="slider_link"/>',
                                             '<parent link="ground"/><child link="rod_link"/>'), "two parent joints"),
    "negative mass": (SLIDER_CRANK.replace('<mass value="0.4"/>', '<mass value="-1"/>'), "mass -1"),
    "zero mass with inertia": (SLIDER_CRANK.replace('<mass value="0.4"/>', '<mass value="0"/>'), "mass 0"),
    "inertia not positive definite": (SLIDER_CRANK.replace('ixx="2e-5"', 'ixx="-2e-5"'), "positive definite"),
}


@pytest.mark.parametrize("case", list(URDF_CASES))
def test_bad_urdf_is_a_named_error(case, tmp_path):
    text, needle = URDF_CASES[case]
    with pytest.raises(MalformedDescription, match=needle.replace("(", r"\(")):
        mechkit.load(written(tmp_path, text))
