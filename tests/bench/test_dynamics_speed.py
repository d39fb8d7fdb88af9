"""`mechkit.bench.dynamics_speed` (timed ones run on demand: -m bench; they print their figures, nothing
here asserts a time). The targets' arithmetic of issues 13, 21 and 33 is checked on made-up rows."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.bench import dynamics_speed
from mechkit.bench.dynamics_speed import SpeedRow
from mechkit.bench.sampling import make_samples

ALL_MISSED = {
    "one sample of inverse dynamics / raw",
    "forward_dynamics wrapper / raw",
    "exact forward dynamics / MuJoCo mj_forward",
    "determinacy on / off, one sample",
}


def test_targets_carry_each_mechanisms_limits():
    """Issue 33's limits: one sample of inverse dynamics 8x raw on the four-bar, 5x on the 2T1R, 1x on
    the deployable (where batched is 1x too, the exact forward dynamics is held to mj_forward and the
    inverse dynamics with determinacy to 2x raw); the wrapper 2x raw, batched 1.5x."""
    rows = [
        SpeedRow(label, 1.0, ratio)
        for label, ratio in (
            (dynamics_speed.ONE, 6.0),
            (dynamics_speed.ONE_DET, 2.5),
            (dynamics_speed.BATCHED, 2.0),
            (dynamics_speed.FORWARD, 3.5),
            (dynamics_speed.EXACT, 0.5),
            (dynamics_speed.MJ_FORWARD, 0.25),
        )
    ]
    limits = {
        name: {t.label: (t.limit, t.met) for t in dynamics_speed.targets(rows, name)}
        for name in ("four_bar", "parallel_2t1r", "deployable_9rr12uru", "tetra_3rr3uru")
    }
    assert limits["four_bar"]["one sample of inverse dynamics / raw"] == (8.0, True)
    assert limits["parallel_2t1r"]["one sample of inverse dynamics / raw"] == (5.0, False)
    assert "one sample of inverse dynamics / raw" not in limits["tetra_3rr3uru"]
    assert limits["four_bar"]["forward_dynamics wrapper / raw"] == (2.0, False)
    assert limits["four_bar"]["batched inverse dynamics per sample / raw"] == (1.5, False)
    assert limits["deployable_9rr12uru"]["batched inverse dynamics per sample / raw"] == (1.0, False)
    assert limits["deployable_9rr12uru"]["inverse dynamics with determinacy / raw"] == (2.0, False)
    assert "inverse dynamics with determinacy / raw" not in limits["four_bar"]
    assert limits["deployable_9rr12uru"]["exact forward dynamics / MuJoCo mj_forward"] == (1.0, False)
    assert "exact forward dynamics / MuJoCo mj_forward" not in limits["four_bar"]


@pytest.mark.bench
def test_dynamics_speed_rows(load_cached):
    result = dynamics_speed.measure(load_cached("four_bar"), budget=0.05, repeats=5)
    labels = {r.label for r in result.rows}
    assert {dynamics_speed.RAW, dynamics_speed.BATCHED, dynamics_speed.EXACT} <= labels
    assert all(np.isfinite(r.us) and r.us > 0 for r in result.rows)
    print("\n".join(dynamics_speed.markdown([result])))


@pytest.mark.bench
@pytest.mark.parametrize("name", ["four_bar", "deployable_9rr12uru"])
def test_the_breakdown_times_every_step_of_the_missed_calls(name, load_cached):
    m = load_cached(name)
    found = dynamics_speed.phases(m, make_samples(m, 3), ALL_MISSED, budget=0.02, repeats=3)
    calls = {p.call for p in found}
    assert calls == {dynamics_speed.ONE, dynamics_speed.FORWARD, dynamics_speed.EXACT, dynamics_speed.ONE_DET}
    for call in calls:
        steps = [p for p in found if p.call == call]
        assert steps[0].share == 1.0 and steps[-1].label.startswith("the rest of the core")
        assert all(np.isfinite(p.us) for p in steps)
    print("\n".join(dynamics_speed.markdown([dynamics_speed.MechanismSpeed(name, m.model.nv, [], [], found)])))
