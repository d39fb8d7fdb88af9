"""Four-bar designs evaluated in one chunk, as a worker would (the rows of the sweep's table)."""

from __future__ import annotations

import numpy as np

import mechkit
from mechkit.sweep import Study
from mechkit.sweep.evaluate import Chunk, evaluate_chunk
from mechkit.sweep.specific import resolve


def four_bar_rows(values, study=None, metrics=None):
    """The rows of four-bar designs (crank, ground, coupler, rocker: as many as each design gives) and the
    metric columns."""
    study = study or Study(law="turn", samples=60)
    mech = mechkit.load("four_bar")
    chosen = resolve("four_bar", metrics)
    columns = tuple(c for m in chosen for c in m.columns(mech))
    names = ("crank", "ground", "coupler", "rocker")[: len(values[0])]
    chunk = Chunk(
        "four_bar",
        {},
        names,
        tuple(range(len(values))),
        np.array(values, float),
        study,
        tuple(m.name for m in chosen),
        columns,
    )
    return evaluate_chunk(chunk), columns
