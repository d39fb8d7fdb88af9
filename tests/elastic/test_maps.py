"""Stiffness maps: each cell is the stiffness at its assembled pose; a plot is written."""

from __future__ import annotations

import numpy as np

import mechkit
from mechkit.elastic import ElasticModel
from mechkit.elastic.maps import plot_map, stiffness_map


def test_five_bar_map_cells_are_the_stiffness_at_their_poses(tmp_path):
    m = mechkit.load("five_bar")
    e = ElasticModel(m)
    home = m.joint_values(m.home_q)
    grid = {
        "prox1": home["prox1"] + np.array([-0.05, 0.0, 0.05]),
        "prox2": home["prox2"] + np.array([-0.05, 0.0, 0.05]),
    }
    r = stiffness_map(e, "dist1_link", grid, [0.22, 0.0, 0.0])
    assert not np.isnan(r.held).any()
    q = m.assemble({"prox1": grid["prox1"][2], "prox2": grid["prox2"][0]})
    direct = e.stiffness(q, "dist1_link", [0.22, 0.0, 0.0])
    assert np.allclose(r.held[2, 0], direct.held, rtol=1e-9) and np.allclose(r.free[2, 0], direct.free, rtol=1e-9)
    assert np.ptp(r.free[..., 2]) > 0.01 * r.free[..., 2].max()  # the stiffness does change over the workspace
    assert plot_map(r, "z", tmp_path / "map.png").stat().st_size > 10_000
