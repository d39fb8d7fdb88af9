"""`mechkit.bench.ladder`: the ladder of four-bar loops timed (run on demand: -m bench; it prints its
figures, nothing here asserts a time)."""

from __future__ import annotations

import pytest

from mechkit.bench import ladder


@pytest.mark.bench
def test_ladder_rows():
    points = ladder.run((1, 2, 4, 8), budget=0.02, repeats=3)
    assert all(p.lcaba_error <= 1e-10 for p in points)
    print("\n".join(ladder.markdown(points)))
