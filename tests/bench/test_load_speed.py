"""`mechkit.bench.load_speed`: file loads against name loads (figures printed; run with -m bench)."""

from __future__ import annotations

import pytest

from mechkit.bench.load_speed import lines, load_times


@pytest.mark.bench
def test_load_times_print_the_ratio_of_each_route():
    rows = load_times(("four_bar",), repeats=3)
    print("\n".join(lines(rows)))
    assert [r.route for r in rows] == ["name", "urdf", "extended-urdf", "mjcf"]
    assert rows[0].ratio == 1.0 and all(r.median_s > 0 and r.nv == 3 and r.loops == 1 for r in rows)
