"""`mechkit.simulation.recorder`: the samples of a run: the efforts of joints driven part of the time, the
samples grouped by what drives them, and every sample's reactions from the core's inverse dynamics
(against the efforts the dynamics found, and Newton's law for the whole mechanism)."""

from __future__ import annotations

import numpy as np

from mechkit import simulation
from mechkit.simulation.recorder import Recorder
from mechkit.simulation.state_layout import StateLayout


def test_a_joint_held_mid_run_gets_its_effort_column_and_its_group(load_cached):
    """The five-bar recorded free, then with prox1 held: the effort column is NaN before and the holding
    effort after; the samples group by their drives, and the core's inverse dynamics of the held sample
    gives back the effort the forward dynamics found; each sample's energies are the system's."""
    m = load_cached("five_bar")
    system = simulation.MechanismSystem(m, [], simulation.Drives(), "kkt")
    layout = StateLayout(m.model, 1)
    recorder = Recorder(system, layout, simulation.Projection(m))
    q = m.assemble([2.0, 1.2])
    v = m.velocities(q, [0.5, -0.4])
    recorder.record(0.0, layout.pack(q, v, np.zeros(1)), {})
    system.drives = system.drives.holding("prox1", 2.0)
    recorder.holding("prox1")
    v_held = m.velocities(q, [0.0, -0.4])
    recorder.record(0.1, layout.pack(q, v_held, np.zeros(1)), {})
    recorder.event(0.1, "latch:prox1", "latched")
    r = recorder.arrays()
    assert recorder.effort_names == ["prox1"] and r["efforts"].shape == (2, 1)
    assert np.isnan(r["efforts"][0, 0]) and np.isfinite(r["efforts"][1, 0])
    groups = recorder.groups()
    assert {k: v.tolist() for k, v in groups.items()} == {(): [0], ("prox1",): [1]}
    out = recorder.system_reactions(m.closure_model.with_actuation(("prox1",)), groups[("prox1",)], r)
    assert np.allclose(out.efforts[:, 0], r["efforts"][1], rtol=1e-9, atol=1e-12)
    assert r["kinetic"].tolist() == [system.kinetic(q, v), system.kinetic(q, v_held)]
    assert r["residual"].max() < 1e-12 and recorder.events == [(0.1, "latch:prox1", "latched")]


def test_reactions_balance_the_motion(four_bar, free):
    """Every sample's support reactions carry the weight and the centre of mass's acceleration."""
    from conftest import support_balance_error

    for k in (0, len(free.t) // 3, len(free.t) - 1):
        m = free.motion
        assert support_balance_error(four_bar, m.q[k], m.v[k], m.a[k]) < 1e-9
