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


def test_a_metric_without_a_finite_value_fails_the_design_naming_it():
    """A sweep used to mark such a design `ok` with its metric NaN."""
    from mechkit.sweep.evaluate import _judged

    assert _judged({"a": 1.0, "b": 2.0}) == {"status": "ok", "message": ""}
    assert _judged({"a": 1.0, "stiffness.x": math.inf, "b": math.nan}) == {
        "status": "failed",
        "message": "no finite value of stiffness.x, b",
    }


def test_an_elastic_metric_of_a_mechanism_with_nothing_elastic_is_an_error_saying_so():
    """The rocket gimbal has no beam: its first frequency used to be NaN in an `ok` row."""
    import numpy as np

    import mechkit
    from mechkit.sweep import Study
    from mechkit.sweep.evaluate import Chunk, evaluate_chunk

    mech = mechkit.load("rocket_gimbal")
    name = next(iter(mech.params.__dataclass_fields__))
    chunk = Chunk(
        "rocket_gimbal",
        {},
        (name,),
        (0,),
        np.array([[getattr(mech.params, name)]], float),
        Study(),
        ("first_frequency",),
        ("first_frequency",),
    )
    (row,) = evaluate_chunk(chunk)
    assert row["status"] == "error" and math.isnan(row["first_frequency"])
    assert "MethodUnavailable" in row["message"] and "no <mechkit:beam>" in row["message"]
