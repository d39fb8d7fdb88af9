"""Shared fixtures: mechanisms are built once per session (xacro and assembly are the slow part)."""

from __future__ import annotations

import functools

import pytest

import mechkit


@functools.cache
def built(name: str, **params) -> mechkit.Mechanism:
    return mechkit.load(name, **params)


@pytest.fixture(scope="session")
def load_cached():
    """mechkit.load with a cache keyed by name and parameters."""

    def load(name: str, **params):
        return built(name, **params)

    return load
