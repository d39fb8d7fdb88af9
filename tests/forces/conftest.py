"""The mechanism the force elements' tests load them on: the four-bar, built once per session."""

from __future__ import annotations

import pytest


@pytest.fixture(scope="module")
def four_bar(load_cached):
    return load_cached("four_bar")
