"""`mechkit.bench.methods`: every mechanism's own methods against the reference of their quantity."""

from __future__ import annotations

import pytest

from mechkit.bench import timing
from mechkit.bench.methods import own_methods, references
from mechkit.bench.sampling import make_samples
from mechkit.catalog.registry import names

#: Largest error of a mechanism's own method against the bench's reference, per quantity (rad or m;
#: relative for dynamics). The trusses' fold is quasi-static (|a| ~ 1e-6 rad/s^2): none of their own
#: methods is a forward dynamics.
AGREEMENT = {"assembly": 1e-9, "inverse_kinematics": 1e-9, "forward_dynamics": 1e-8, "inverse_dynamics": 1e-8}


@pytest.mark.parametrize("name", names())
def test_every_declared_bench_method_agrees_with_the_reference(name, load_cached):
    """Each mechanism's own methods (the papers' closed forms, SOC, Lagrange) run on the bench's states
    and agree with the reference of their quantity (the spec's own where it declares one, else the core's)."""
    mech = load_cached(name)
    samples = make_samples(mech, 2)
    refs = references(mech, samples)
    for method in own_methods(mech):
        row = timing.measure(mech, method, samples, refs, budget_s=1e-4, repeats=1)
        assert row.outcome == "ok", (name, method.name, row.outcome)
        assert row.error < AGREEMENT[method.quantity], (name, method.name, row.error)
