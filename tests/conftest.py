"""Shared fixtures: mechanisms are built once per session (xacro and assembly are the slow part)."""

from __future__ import annotations

import os

# One BLAS thread: the core's linear algebra is on small matrices, where OpenBLAS's worker threads only
# contend (a 60 x 59 SVD took 100 ms instead of 1 ms with two threads on a loaded two-core machine).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

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


def support_balance_error(m: mechkit.Mechanism, q, v, a) -> float:
    """Relative error of Newton's second law for the whole mechanism, from the support reactions:
    sum of ground reactions = total mass x (COM acceleration - gravity)."""
    import numpy as np
    import pinocchio as pin

    inv = m.inverse_dynamics(q, v, a)
    data = m.model.createData()
    pin.centerOfMass(m.model, data, q, v, a)
    supports = sum(r.wrench[:3] for r in inv.reactions.values() if r.support)
    expected = data.mass[0] * (data.acom[0] - m.model.gravity.linear)
    return float(np.max(np.abs(supports - expected)) / max(1.0, np.max(np.abs(expected))))


def assert_failures_named(cases) -> None:
    """A failure study's cases: some, each finite and ok (or on another branch), or naming how it failed
    (an exception's class, "non-finite", "root lost"): never a silent NaN."""
    import numpy as np

    from mechkit.base import exceptions

    known = {"ok", "other branch", "root lost"} | {n for n in dir(exceptions) if n[0].isupper()}
    assert cases
    for c in cases:
        assert c.outcome in known, c
        assert np.isfinite(c.error) == (c.outcome in ("ok", "other branch")), c
