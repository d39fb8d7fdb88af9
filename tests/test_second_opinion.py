"""The automatic SOC decomposition (`mechkit.second_opinion`): the Dulmage-Mendelsohn form is a valid,
irreducible block-triangular form; the 2T1R's SKCs are the paper's; efforts and determinate reactions
agree with constrained RNEA over each built-in mechanism's scene, and both methods call the same
components indeterminate."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components, maximum_bipartite_matching

import mechkit
from mechkit.base.exceptions import InvalidParameters
from mechkit.second_opinion.agreement import agreement, scene_states
from mechkit.second_opinion.decomposition import block_triangular
from mechkit.second_opinion.opinion import SecondOpinion

TOL = 1e-8


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
    assert groups[:3] == [({"link41", "link42"}, {"R43"}, set()), ({"link32", "platform"}, {"R23", "R32"}, set()),
                          ({"link12", "link22"}, {"R12", "R22"}, set())]
    assert sorted(groups[3:], key=lambda g: sorted(g[0])) == [({"link11"}, set(), {"R11"}), ({"link21"}, set(), {"R21"}),
                                                              ({"link31"}, set(), {"R31"})]


def test_component_level_is_finer_and_agrees():
    mech = mechkit.load("parallel_2t1r")
    fine, skc = SecondOpinion(mech, level="component"), SecondOpinion(mech)
    assert len(fine.skcs) > len(skc.skcs)
    states = scene_states(mech, 3)
    assert agreement(fine, states, timing=False).max_relative_difference < TOL


def test_unknown_level_is_a_named_error():
    with pytest.raises(InvalidParameters, match="level"):
        SecondOpinion(mechkit.load("four_bar"), level="atoms")


# name -> (samples, scene) of the default run; the scenes of ten_bar, tetra and deployable take
# seconds to minutes to build (a simulated deployment, 201-pose folds), so the default run uses their
# generic sweep; the slow test runs every mechanism's own first scene.
FAST = {"four_bar": (6, None), "five_bar": (6, None), "parallel_2t1r": (6, None), "rocket_gimbal": (6, None),
        "spherical_2dof": (6, None), "ten_bar": (4, "sweep"), "tetra_3rr3uru": (2, "sweep"),
        "deployable_9rr12uru": (2, "sweep")}


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


def test_redundant_constraints_report_the_indeterminate_block():
    """The deployable (one redundant constraint) is one under-determined block with a one-dimensional
    self-stress; the planar linkages' out-of-plane rows are under-determined blocks."""
    deployable = SecondOpinion(mechkit.load("deployable_9rr12uru"))
    (block,) = deployable.skcs
    assert block.kind == "under" and len(block.unknowns) - block.equations == 1
    for name in ("four_bar", "five_bar", "ten_bar"):
        under = [s for s in SecondOpinion(mechkit.load(name)).skcs if s.kind == "under"]
        assert under and all(len(s.unknowns) > s.equations for s in under)
