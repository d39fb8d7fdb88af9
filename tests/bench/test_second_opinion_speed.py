"""The second opinion's benchmark rows: the one-off decomposition cost and the per-sample solve times
come back as figures, with the agreement measured on the same states."""

from __future__ import annotations

from mechkit.bench.second_opinion_speed import lines, second_opinion_rows


def test_rows_give_the_figures_and_the_agreement():
    (row,) = second_opinion_rows(["four_bar"], samples=3, budget_s=0.05, repeats=2)
    assert row.name == "four_bar" and row.skcs == 2 and row.largest == 12
    assert row.decompose_ms > 0 and row.soc_us > 0 and row.rnea_us > 0
    assert abs(row.ratio - row.soc_us / row.rnea_us) < 1e-12
    assert row.samples == 3 and row.max_relative_difference < 1e-8
    table = lines([row])
    assert len(table) == 3 and table[2].startswith("| four_bar | 2 | 12 |")
