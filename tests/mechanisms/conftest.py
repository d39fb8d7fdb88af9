"""Fixtures of the mechanism packages' tests: `mech`, the mechanism a test file is about (named by its
folder, tests/mechanisms/<name>/, or its file, tests/mechanisms/test_<name>.py), and the truss folds that
the unit's, the composite's and the truss package's tests share (computed once)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechkit.mechanisms.truss.fold import fold, fold_times

from .truss.paper import TIMES


@pytest.fixture(scope="module")
def mech(request, load_cached):
    path = Path(request.module.__file__)
    return load_cached(path.stem.removeprefix("test_") if path.parent.name == "mechanisms" else path.parent.name)


@pytest.fixture(scope="session")
def unit(load_cached):
    """The 3RR-3URU unit."""
    return load_cached("tetra_3rr3uru")


@pytest.fixture(scope="session")
def unit_fold(unit):
    """The unit's fold at `truss.paper.TIMES`."""
    return fold(unit, np.array(TIMES))


@pytest.fixture(scope="session")
def coarse_fold(load_cached):
    """The 9RR-12URU composite's fold every 25 s."""
    return fold(load_cached("deployable_9rr12uru"), fold_times(25.0))
