"""`mechkit.second_opinion.decomposition`: the Dulmage-Mendelsohn form is a valid, irreducible
block-triangular form; the 2T1R's SKCs are the paper's; redundant constraints give indeterminate
blocks; against the hand-written decompositions (the papers' own, kept as they are), every automatic
SKC lies inside one hand-written SKC, and where a hand-written SKC holds several automatic ones the
automatic decomposition splits it finer."""

from __future__ import annotations

import importlib
import warnings

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components, maximum_bipartite_matching

import mechkit
from mechkit.base.exceptions import InvalidParameters
from mechkit.second_opinion.decomposition import block_triangular
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


def _random_pattern(rng: np.random.Generator) -> sp.csr_matrix:
    m, n = rng.integers(3, 14, size=2)
    dense = rng.random((m, n)) < rng.uniform(0.1, 0.4)
    return sp.csr_matrix(dense.astype(float))


@pytest.mark.parametrize("seed", range(40))
def test_dulmage_mendelsohn_blocks_are_a_finest_block_triangular_form(seed):
    pattern = _random_pattern(np.random.default_rng(seed))
    dense = pattern.toarray() != 0
    blocks = block_triangular(pattern)
    rows = [r for _, rs, _ in blocks for r in rs]
    cols = [c for _, _, cs in blocks for c in cs]
    assert sorted(rows) == list(range(dense.shape[0])) and sorted(cols) == list(range(dense.shape[1]))
    solved: set[int] = set()
    for kind, rs, cs in blocks:
        # each block's rows use only its own and earlier blocks' unknowns
        used = set(np.flatnonzero(dense[rs].any(axis=0)))
        assert used <= solved | set(cs), (kind, rs, cs)
        solved |= set(cs)
        sub = sp.csr_matrix(dense[np.ix_(rs, cs)].astype(float))
        matched = int(np.sum(maximum_bipartite_matching(sub, perm_type="column") >= 0)) if rs and cs else 0
        if kind == "determined":
            assert len(rs) == len(cs) == matched  # structurally non-singular
            # irreducible: the matched digraph is strongly connected
            col_of_row = maximum_bipartite_matching(sub, perm_type="column")
            order = np.argsort(col_of_row)
            graph = sp.csr_matrix(dense[np.ix_(rs, cs)][order].astype(float))
            assert connected_components(graph, directed=True, connection="strong")[0] == 1
        elif kind == "under":
            assert len(cs) > len(rs) == matched
        else:
            assert len(rs) > len(cs) == matched


def _bodies(opinion: SecondOpinion) -> list[tuple[set[str], set[str], set[str]]]:
    return [(set(s.bodies), set(s.released), set(s.actuators)) for s in opinion.skcs if s.kind == "determined"]


def test_2t1r_skcs_are_the_papers():
    """Section 4.3: limb III released at R43, then limb II with the platform released at R23 (M3),
    then limb I (M1, M2); the out-of-plane rows form the indeterminate block."""
    opinion = SecondOpinion(mechkit.load("parallel_2t1r"))
    assert _bodies(opinion) == [
        ({"link41", "link42"}, {"R43"}, set()),
        ({"link31", "link32", "platform"}, {"R23"}, {"R31"}),
        ({"link11", "link12", "link21", "link22"}, set(), {"R11", "R21"}),
    ]
    under = [s for s in opinion.skcs if s.kind == "under"]
    assert len(under) == 1 and len(under[0].unknowns) > under[0].equations
    labels = under[0].unknown_labels(opinion.structure)
    assert all(label.split(".")[1] in ("fy", "mx", "mz") for label in labels)


def test_2t1r_body_level_splits_the_driving_links_off():
    """Without joining each driving link to the chain it drives, the finest body-level form solves
    the motor links last, each from its own equilibrium."""
    opinion = SecondOpinion(mechkit.load("parallel_2t1r"), level="body")
    groups = _bodies(opinion)
    assert groups[:3] == [
        ({"link41", "link42"}, {"R43"}, set()),
        ({"link32", "platform"}, {"R23", "R32"}, set()),
        ({"link12", "link22"}, {"R12", "R22"}, set()),
    ]
    assert sorted(groups[3:], key=lambda g: sorted(g[0])) == [
        ({"link11"}, set(), {"R11"}),
        ({"link21"}, set(), {"R21"}),
        ({"link31"}, set(), {"R31"}),
    ]


def test_unknown_level_is_a_named_error():
    with pytest.raises(InvalidParameters, match="level"):
        SecondOpinion(mechkit.load("four_bar"), level="atoms")


def test_redundant_constraints_report_the_indeterminate_block():
    """The deployable (one redundant constraint) is one under-determined block with a one-dimensional
    self-stress; the planar linkages' out-of-plane rows are under-determined blocks."""
    deployable = SecondOpinion(mechkit.load("deployable_9rr12uru"))
    (block,) = deployable.skcs
    assert block.kind == "under" and len(block.unknowns) - block.equations == 1
    for name in ("four_bar", "five_bar", "ten_bar"):
        under = [s for s in SecondOpinion(mechkit.load(name)).skcs if s.kind == "under"]
        assert under and all(len(s.unknowns) > s.equations for s in under)
