"""The idealisation: which bodies are beams (joints counted by joint, not by point)."""

from __future__ import annotations

import pytest

import mechkit
from mechkit.base.exceptions import InvalidParameters
from mechkit.elastic import ElasticModel


def test_2t1r_link22_and_platform_are_rigid():
    """link22 carries R22, R23 and R13 (two of them at C1): three joints, rigid; the platform too."""
    e = ElasticModel(mechkit.load("parallel_2t1r"))
    links = {b.link for b in e.idealisation.elastic}
    assert links == {"link11", "link12", "link21", "link31", "link32", "link41", "link42"}
    assert all(abs(length - 0.1) < 1e-12 for b in e.idealisation.elastic for length in b.lengths)


def test_a_section_on_a_body_the_idealisation_keeps_rigid_is_refused_saying_what_can_be_a_beam():
    """It used to be dropped in silence: the result did not change, and nothing said why."""
    m = mechkit.load("parallel_2t1r")
    e = ElasticModel(m)
    section = e.data.sections["link21"]
    with pytest.raises(InvalidParameters, match="'link22'.*carries 3 joints.*give the section to one of") as err:
        e.with_section("link22", section)
    assert "'link11'" in str(err.value) and "'platform'" not in str(err.value).split("one of")[1]
    with pytest.raises(InvalidParameters, match="'base'.*is the ground"):
        e.with_section("base", section)


def test_deployable_rods_and_uru_links_are_beams():
    e = ElasticModel(mechkit.load("deployable_9rr12uru"))
    assert len(e.idealisation.elastic) == 9 + 24
