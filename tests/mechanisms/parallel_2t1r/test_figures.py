"""`mechkit.mechanisms.parallel_2t1r.figures`: the comparison and singular studies drawn."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.parallel_2t1r.compare import compare_along

REGULAR = np.arange(1, 501) * 0.01  # the 501-sample law without its singular start t = 0


@pytest.fixture(scope="module")
def comparison(mech):
    return compare_along(mech, REGULAR)


def test_studies_write_both_figures(mech, tmp_path):
    """The comparison (10 samples) and the singular studies drawn (moved from test_parallel_2t1r_tools.py)."""
    from mechkit.mechanisms.parallel_2t1r.figures import comparison_figure, singular_figure
    from mechkit.mechanisms.parallel_2t1r.studies import comparison, singular

    comparison_figure(comparison(mech, 10), tmp_path)
    singular_figure(singular(mech), tmp_path)
    for name in ("comparison", "singular"):
        png = tmp_path / f"parallel_2t1r_{name}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000
