"""`mechkit.mechanisms.parallel_2t1r.scenes`: the motion-law scene closes every loop; the paper's example
drawn side by side, every assembly the solver closes."""

from __future__ import annotations

import numpy as np

from mechkit import viz
from mechkit.mechanisms.parallel_2t1r.scenes import example_configurations
from mechkit.scenes import scene_poses


def test_motion_law_scene_closes_every_loop(mech):
    poses = scene_poses(mech, "motion_law")  # checks sizes, finiteness and closure
    assert len(poses) == 101
    np.testing.assert_allclose([q[mech.q_index("R21")] for q in poses], np.pi / 15 * np.linspace(0, 5, 101), atol=1e-15)


def test_every_example_assembly_is_drawn_side_by_side(load_cached):
    mech = load_cached("parallel_2t1r")
    configurations = example_configurations(mech)
    assert len(configurations) == 6  # 3 reachable poses x 2 theta4 roots (pose 4: limb III cannot reach)
    for q in configurations:
        assert np.max(np.abs(mech.closure_residual(q))) < 1e-12
    html = viz.side_by_side(mech, configurations)
    assert html.startswith("<!DOCTYPE html>") and "MeshCat.Viewer" in html
    assert len({tuple(np.round(q, 9)) for q in configurations}) == 6  # six distinct assemblies
