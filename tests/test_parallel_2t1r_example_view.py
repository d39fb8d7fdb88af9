"""The paper's example drawn side by side: every assembly the solver closes, in one page."""

from __future__ import annotations

import numpy as np

from mechkit import viz
from mechkit.mechanisms.parallel_2t1r.scenes import example_configurations


def test_every_example_assembly_is_drawn_side_by_side(load_cached):
    mech = load_cached("parallel_2t1r")
    configurations = example_configurations(mech)
    assert len(configurations) == 6  # 3 reachable poses x 2 theta4 roots (pose 4: limb III cannot reach)
    for q in configurations:
        assert np.max(np.abs(mech.closure_residual(q))) < 1e-12
    html = viz.side_by_side(mech, configurations)
    assert html.startswith("<!DOCTYPE html>") and "MeshCat.Viewer" in html
    assert len({tuple(np.round(q, 9)) for q in configurations}) == 6  # six distinct assemblies
