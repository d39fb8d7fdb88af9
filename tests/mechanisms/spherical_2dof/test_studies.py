"""`mechkit.mechanisms.spherical_2dof.studies` and their figures."""

from __future__ import annotations


def test_studies_draw_their_figures(mech, tmp_path):
    """The cone scene and the basins on tiny runs, drawn."""
    from mechkit.mechanisms.spherical_2dof.figures import basin_figure, cone_figure
    from mechkit.mechanisms.spherical_2dof.studies import basin, cone, cone_summary

    c = cone(mech, samples=6)
    summary = cone_summary(c)
    assert summary["torques Pinocchio vs SOC (N m)"] < 1e-12 and summary["FK vs plan, attitude (rad)"] < 1e-12
    for path in (*cone_figure(c, tmp_path), *basin_figure(basin(mech, directions=2, grid_points=11), tmp_path)):
        assert path.stat().st_size > 10_000
