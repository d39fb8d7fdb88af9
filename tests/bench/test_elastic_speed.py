"""`mechkit.bench.elastic_speed`: the timed elastic quantities on a tiny budget (their timings are figures,
never asserted): each row's verdict is its target applied to its own times, and the table has one line per
row with the ratio of the times it shows."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechkit.bench import elastic_speed


def _check(rows):
    for r in rows:
        assert r.us > 0
        if "x rigid" in r.target:
            assert r.reference_us > 0 and r.met == (r.us <= 3 * r.reference_us)
        else:
            limit = float(r.target.removeprefix("< ").removesuffix(" us"))
            assert math.isnan(r.reference_us) and r.met == (r.us < limit)
    table = elastic_speed.lines(rows)
    assert len(table) == 2 + len(rows) and all(line.count("|") == table[0].count("|") for line in table)
    for r, line in zip(rows, table[2:]):
        cells = [c.strip() for c in line.strip("|").split("|")]
        assert cells[0] == r.label and cells[5] == ("yes" if r.met else "no")
        if not np.isnan(r.reference_us):
            assert float(cells[3]) == pytest.approx(r.us / r.reference_us, abs=0.006)


def test_every_row_on_a_tiny_budget():
    """Every row of the page section: the compliant reactions against the rigid batch (four-bar, 2T1R,
    deployable truss), the 2T1R platform's stiffness, the deployable truss's modes."""
    rows = elastic_speed.rows(budget_s=0.02, repeats=1)
    assert [r.label.split(":")[0] for r in rows] == [
        "four_bar",
        "parallel_2t1r",
        "deployable_9rr12uru",
        "parallel_2t1r",
        "deployable_9rr12uru",
    ]
    _check(rows)
