"""The automatic decomposition against the hand-written ones (the papers' own, kept as they are):
every automatic SKC lies inside one hand-written SKC, and where a hand-written SKC holds several
automatic ones the automatic decomposition splits it finer."""

from __future__ import annotations

import importlib
import warnings

import numpy as np
import pytest

import mechkit
from mechkit.second_opinion.opinion import SecondOpinion


def _2t1r(mech):
    from mechkit.mechanisms.parallel_2t1r.motion_law import motion_law, state_at
    from mechkit.mechanisms.parallel_2t1r.soc import skcs

    return skcs(mech.params, state_at(mech.params, *motion_law(1.0)))


def _planar(mech):
    from mechkit.bench.sampling import make_samples
    from mechkit.mechanisms.planar_linkage.state import state
    from mechkit.validation.planar_soc import soc_skcs

    motion = importlib.import_module(f"mechkit.mechanisms.{mech.spec.name}.closed_form").motion
    return soc_skcs(state(motion, mech, make_samples(mech, 1)[0]))


def _spherical(mech):
    from mechkit.mechanisms.spherical_2dof import soc

    return soc.skcs(mech.params, [0.1, 0.2], [0.0, 0.0], [0.0, 0.0], {"r11": 0.0, "r21": 0.0})


def _tetra(mech):
    from mechkit.mechanisms.tetra_3rr3uru import soc

    return soc.skcs(soc.UnitMotion(mech.params), soc.model_inertias(mech), 0.5)


def _ten_bar(mech):
    from mechkit.mechanisms.ten_bar import dynamics, soc
    from mechkit.mechanisms.ten_bar.lagrange_model import lagrange_linkage

    q, v = dynamics.lagrange_state(mech.params, mech.home_q, np.zeros(mech.model.nv), mech)
    return soc.skc_instants(lagrange_linkage(mech.params), q, v, np.zeros_like(v))


def _rocket(mech):
    from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene
    from mechkit.mechanisms.rocket_gimbal.soc import soc_skcs

    scene = SwingScene()
    return soc_skcs(mech.params, scene.motion(mech.params, 0.3), scene)


# name -> (hand-written SKCs, level compared, hand-written SKCs the automatic one splits)
CASES = {
    "parallel_2t1r": (_2t1r, "skc", []),
    "four_bar": (_planar, "body", []),
    "five_bar": (_planar, "body", []),
    "spherical_2dof": (_spherical, "body", ["mechanism"]),
    "tetra_3rr3uru": (_tetra, "skc", []),
    "ten_bar": (_ten_bar, "body", ["dyad", "four_bar", "rocker"]),
    "rocket_gimbal": (_rocket, "skc", ["servo_loops"]),
}


def _link(name: str) -> str:
    """The hand-written modules call the planar calibration links without the URDF's "_link"."""
    return name.removesuffix("_link")


@pytest.mark.parametrize("name", sorted(CASES))
def test_automatic_equals_or_refines_the_hand_written(name):
    build, level, split = CASES[name]
    mech = mechkit.load(name)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        hand = [(k.name, {_link(b.name) for b in k.bodies}) for k in build(mech)]
    auto = [{_link(b) for b in s.bodies} for s in SecondOpinion(mech, level=level).skcs if s.kind == "determined"]
    inside = {}
    for bodies in auto:
        home = [label for label, group in hand if bodies <= group]
        assert home, f"automatic SKC {sorted(bodies)} lies in no hand-written SKC of {name}"
        inside.setdefault(home[0], []).append(bodies)
    assert sorted(label for label, parts in inside.items() if len(parts) > 1) == split, inside
    # the hand-written SKCs that solve the efforts hold exactly the automatic SKCs inside them
    for label, group in hand:
        if label in inside and label not in split:
            assert inside[label] == [group], (label, inside[label])
