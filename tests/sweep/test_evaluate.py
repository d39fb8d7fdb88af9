"""`mechkit.sweep.evaluate`: a failing design is a row with its status and message."""

from __future__ import annotations

import math

from .chunks import four_bar_rows


def test_failing_designs_are_rows_with_their_status():
    rows, columns = four_bar_rows(
        [
            [0.10, 0.30, 0.28, 0.22],  # the default crank-rocker
            [0.25, 0.30, 0.30, 0.05],  # at the home crank angle C is 0.17 m from D < 0.30 - 0.05
            [0.20, 0.40, 0.28, 0.22],  # assembles, but the crank cannot turn fully: a dead point
            [-0.1, 0.30, 0.28, 0.22],  # invalid parameter
            [0.10, 1.00, 0.28, 0.22],
        ]
    )  # ground longer than the three others (params refuse it)
    assert [r["status"] for r in rows] == ["ok", "does_not_assemble", "singular", "error", "error"]
    ok = rows[0]
    assert ok["closure_residual"] < 1e-9 and 0 < ok["singularity_distance"] <= 1 and ok["branch"] in (-1.0, 1.0)
    assert ok["message"] == ""
    for row in rows[1:]:
        assert all(math.isnan(row[c]) for c in columns) and row["message"]
    assert "crank" in rows[3]["message"] and "longest link" in rows[4]["message"]
    assert "ClosureNotConverged" in rows[1]["message"] and "sample" in rows[2]["message"]
