"""`mechkit.sweep.plots`: the Pareto front and the plots of a sweep."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters


def test_pareto_front_and_plots(tmp_path):
    from mechkit.sweep.plots import heat_map, pareto_mask, pareto_plot

    rng = np.random.default_rng(5)
    a, b = rng.random(200), rng.random(200)
    a[3] = np.nan
    front = pareto_mask(a, b)
    assert not front[3] and front.any()
    for i in range(len(a)):  # off the front: beaten by a point of the front; on it: beaten by none
        if np.isnan(a[i]):
            continue
        beaten = front & (a <= a[i]) & (b <= b[i]) & ((a < a[i]) | (b < b[i]))
        assert beaten.any() != front[i]
    import pandas as pd

    frame = pd.DataFrame(
        {
            "x": np.repeat([1.0, 2.0], 2),
            "y": np.tile([1.0, 2.0], 2),
            "m": [1.0, 2.0, 3.0, np.nan],
            "n": [4.0, 3.0, 1.0, np.nan],
            "status": ["ok", "ok", "ok", "singular"],
        }
    )
    assert heat_map(frame, "x", "y", "m", tmp_path / "h.png").stat().st_size > 1000
    assert pareto_plot(frame, "m", "n", tmp_path / "p.png").stat().st_size > 1000
    with pytest.raises(InvalidParameters):
        heat_map(frame, "x", "y", "nope", tmp_path / "h.png")
