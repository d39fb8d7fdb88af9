"""`mechkit.second_opinion.agreement`: efforts and determinate reactions agree with constrained RNEA over
each built-in mechanism's scene, and both methods call the same components indeterminate."""

from __future__ import annotations

import warnings

import pytest

import mechkit
from mechkit.second_opinion.agreement import agreement, scene_states
from mechkit.second_opinion.opinion import SecondOpinion

TOL = 1e-8


def test_component_level_is_finer_and_agrees():
    mech = mechkit.load("parallel_2t1r")
    fine, skc = SecondOpinion(mech, level="component"), SecondOpinion(mech)
    assert len(fine.skcs) > len(skc.skcs)
    states = scene_states(mech, 3)
    assert agreement(fine, states, timing=False).max_relative_difference < TOL


# name -> (samples, scene) of the default run; the scenes of ten_bar, tetra and deployable take
# seconds to minutes to build (a simulated deployment, 201-pose folds), so the default run uses their
# generic sweep; the slow test runs every mechanism's own first scene.
FAST = {
    "four_bar": (6, None),
    "five_bar": (6, None),
    "parallel_2t1r": (6, None),
    "rocket_gimbal": (6, None),
    "spherical_2dof": (6, None),
    "ten_bar": (4, "sweep"),
    "tetra_3rr3uru": (2, "sweep"),
    "deployable_9rr12uru": (2, "sweep"),
}


def _check(name: str, samples: int, scene: str | None) -> None:
    mech = mechkit.load(name)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        states = scene_states(mech, samples, scene=scene)
    result = agreement(SecondOpinion(mech), states, timing=False)
    assert not result.determinacy_mismatches
    assert result.max_relative_difference < TOL, (result.worst, result.max_relative_difference)


@pytest.mark.parametrize("name", sorted(FAST))
def test_agrees_with_constrained_rnea(name):
    _check(name, *FAST[name])


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(FAST))
def test_agrees_with_constrained_rnea_over_the_first_scene(name):
    _check(name, 12, None)
