"""`mechkit.sweep.optimise`: local refinement from the best designs of a sweep."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.sweep import DesignSpace, Study, parse_axis, read, sweep
from mechkit.sweep.evaluate import Chunk, evaluate_chunk


def test_optimise_improves_on_the_best_sweep_design(tmp_path):
    from mechkit.sweep.optimise import optimise

    space = DesignSpace((parse_axis("crank=0.06:0.12:3"), parse_axis("rocker=0.18:0.26:3")))
    study = Study(law="turn", samples=30, period=0.5)
    out = tmp_path / "r"
    sweep("four_bar", space, out, study, ("peak_effort",), workers=1)
    column = "peak_effort.crank"
    frame = read(out)
    refined = optimise(out, column, starts=1, max_evaluations=15, workers=1)[0]
    assert refined.start_value == pytest.approx(frame[frame["status"] == "ok"][column].min())
    assert refined.value <= refined.start_value and 1 < refined.evaluations <= 16
    for axis in space.axes:
        assert axis.lo <= refined.best[axis.name] <= axis.hi
    again = evaluate_chunk(
        Chunk(
            "four_bar",
            {},
            space.names,
            (0,),
            np.array([list(refined.best.values())]),
            study,
            ("peak_effort",),
            ("peak_effort.crank",),
        )
    )[0]
    assert again["status"] == "ok" and again[column] == pytest.approx(refined.value, rel=1e-9)
