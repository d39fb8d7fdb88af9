"""`mechkit.bench.loadtime`: the first load in a fresh process."""

from __future__ import annotations

from mechkit.bench import loadtime


def test_first_load_times_a_fresh_process_and_lists_its_mechanism_modules():
    """Not a timing test: the measurement returns positive times and the imported modules (four_bar's only)."""
    first = loadtime.first_load("four_bar", runs=1)
    assert len(first.process_s) == len(first.inside_s) == 1
    assert 0 < first.inside_s[0] < first.process_s[0]
    assert "mechkit.mechanisms.four_bar" in first.modules
    assert first.others == ()
