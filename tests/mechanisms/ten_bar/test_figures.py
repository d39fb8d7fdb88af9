"""`mechkit.mechanisms.ten_bar.figures`: the deployment's figures."""

from __future__ import annotations

import pytest


@pytest.mark.slow
def test_deployment_figures_written(mech, tmp_path):
    """The deployment's five figures over 0.5 s."""
    from mechkit.mechanisms.ten_bar.figures import deployment_figures
    from mechkit.mechanisms.ten_bar.studies import deployment

    deployment_figures(deployment(mech, t_end=0.5), tmp_path)
    for name in ("poses", "angles", "torques", "supports", "drift"):
        assert (tmp_path / f"ten_bar_{name}.png").stat().st_size > 10_000
