"""What the simulator's tests share, built once per module: the four-bar, and its free motion."""

from __future__ import annotations

import pytest


@pytest.fixture(scope="module")
def four_bar(load_cached):
    return load_cached("four_bar")


@pytest.fixture(scope="module")
def free(four_bar):
    """The four-bar released at home under gravity, 1 s, conservative."""
    return four_bar.simulate(1.0)
