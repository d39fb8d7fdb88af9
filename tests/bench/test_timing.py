"""`mechkit.bench.timing`: the ratio to the fastest method of equal or better accuracy, and the
per-call timer."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.bench import timing
from mechkit.bench.methods import BASELINES, Method
from mechkit.bench.results import Row


def _row(name: str, quantity: str, seconds: float, error: float) -> Row:
    return Row("m", Method(name, quantity, lambda m, s: None), median_s=seconds, error=error)


def test_ratio_to_fastest_of_equal_or_better_accuracy():
    rows = [
        _row("slow exact", "forward_dynamics", 10e-6, 1e-15),
        _row("fast exact", "forward_dynamics", 2e-6, 1e-13),
        _row("fastest sloppy", "forward_dynamics", 1e-6, 1e-2),
        _row(BASELINES["forward_dynamics"], "forward_dynamics", 4e-6, 1e-14),
    ]
    timing.ratios(rows)
    by = {r.method.name: r for r in rows}
    assert by["slow exact"].x_fastest == pytest.approx(5.0)  # both exact within the machine-precision class
    assert by["fast exact"].x_fastest == pytest.approx(1.0)
    assert by["fastest sloppy"].x_fastest == pytest.approx(1.0)  # nothing as fast is as sloppy or better... itself
    assert by["slow exact"].x_base == pytest.approx(2.5)


def test_efforts_only_is_no_yardstick_for_reactions():
    full = _row("with reactions", "inverse_dynamics", 10e-6, 1e-15)
    cheap = _row("efforts only", "inverse_dynamics", 1e-6, 1e-15)
    cheap.note = "efforts only"
    timing.ratios([full, cheap])
    assert full.x_fastest == pytest.approx(1.0) and cheap.x_fastest == pytest.approx(1.0)


def test_time_per_call_counts_every_call():
    calls = []
    times = timing.time_per_call(lambda s: calls.append(s), [1, 2], budget_s=0.01, repeats=3)
    assert times.shape == (3,) and np.all(times > 0)
    assert set(calls) == {1, 2}
