"""`mechkit.simulation.events`: joint limits and latches in a simulation, and the impact they cause: the
velocity jump against its energy identity and the closures, the restitution, the plastic latch."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit import simulation
from mechkit.base.exceptions import InvalidParameters


def test_latch_stops_the_joint_with_a_plastic_impact(four_bar):
    """The crank latching at 0 rad on its way down: one impact takes the whole kinetic energy (one freedom),
    the crank stays there, and the balance still closes."""
    run = four_bar.simulate(0.5, latches=[simulation.Latch("crank", 0.0, -1)])
    assert [e[1] for e in run.events] == ["latch:crank"]
    t_latch = run.events[0][0]
    after = run.t >= t_latch  # the sample at the latch is the state after its impact
    assert np.allclose(run.motion.q[after, four_bar.q_index("crank")], 0.0, atol=1e-12)
    assert np.max(np.abs(run.motion.v[after])) < 1e-9
    assert run.impact_loss[-1] > 0.01
    assert run.energy_error <= 1e-6 * run.energy_scale
    assert np.all(np.isnan(run.motion.effort("crank")[~after])) and np.all(
        np.isfinite(run.motion.effort("crank")[after])
    )


@pytest.mark.parametrize("restitution", [1.0, 0.5])
def test_limits_bounce_by_their_restitution(four_bar, restitution):
    """A stop on the crank at -0.5 rad: it arrives and leaves at restitution times its rate; elastic
    bounces dissipate nothing."""
    lim = simulation.Limit("crank", -0.5, 5.0, restitution)
    run = four_bar.simulate(0.4, limits=[lim], reactions=False)
    bounces = [e for e in run.events if e[1] == "lower:crank"]
    assert bounces
    crank = run.motion.q[:, four_bar.q_index("crank")]
    assert crank.min() >= -0.5 - 1e-9
    i = int(np.searchsorted(run.t, bounces[0][0]))
    rate_after = run.motion.v[i, four_bar.v_index("crank")]
    arrived = float(bounces[0][2].split("arrived at ")[1].split(",")[0])
    assert rate_after == pytest.approx(-restitution * arrived, rel=1e-9)
    if restitution == 1.0:
        assert abs(run.impact_loss[-1]) < 1e-12
    assert run.energy_error <= 1e-6 * run.energy_scale


def _kinetic(m, q, v):
    M = pin.crba(m.model, m.model.createData(), q)
    M = np.triu(M) + np.triu(M, 1).T
    return 0.5 * v @ M @ v


@pytest.mark.parametrize("restitution", [0.0, 0.4, 1.0])
def test_impact_keeps_the_closures_and_its_energy_identity(load_cached, restitution):
    """The five-bar (two freedoms) with prox1 driven at 1 rad/s (its law's rate before and after) and prox2 stopped (or
    bounced): after the jump the loop's velocity rows vanish, prox1 keeps its drive's rate and prox2 has -restitution
    times the rate it arrived with; the kinetic energy changes by the drive's impulsive work minus what the impact
    dissipated, which is >= 0, and 0 for an elastic impact."""
    m = load_cached("five_bar")
    cm = m.closure_model
    q = m.assemble([2.0, 1.2])
    v = m.velocities(q, [1.0, -1.5])
    jv = m.v_index("prox2")
    arrived = v[jv]
    jump = simulation.impact(
        cm, cm.create_data(), q, v, np.array([m.v_index("prox1")]), np.array([1.0]), jv, -restitution * arrived
    )
    assert np.max(np.abs(m.closure_jacobian(q) @ jump.v)) < 1e-12
    assert jump.v[m.v_index("prox1")] == pytest.approx(1.0) and jump.v[jv] == pytest.approx(-restitution * arrived)
    assert _kinetic(m, q, jump.v) - _kinetic(m, q, v) == pytest.approx(jump.drive_work - jump.dissipated, rel=1e-10)
    assert jump.dissipated >= -1e-14 * _kinetic(m, q, v)  # round-off: an elastic impact's 0 came out -1e-17
    if restitution == 1.0:
        assert jump.dissipated == pytest.approx(0.0, abs=1e-12)


def test_a_plastic_impact_of_one_freedom_takes_all_its_kinetic_energy(four_bar):
    """The four-bar (one freedom, nothing driven) with its crank stopped: everything stops, and the impact
    dissipates exactly the kinetic energy there was."""
    m = four_bar
    cm = m.closure_model
    q = m.assemble([0.9])
    v = m.velocities(q, [2.5])
    jump = simulation.impact(cm, cm.create_data(), q, v, np.zeros(0, dtype=int), np.zeros(0), m.v_index("crank"), 0.0)
    assert np.max(np.abs(jump.v)) < 1e-12 and jump.drive_work == 0.0
    assert jump.dissipated == pytest.approx(_kinetic(m, q, v), rel=1e-12)


@pytest.mark.parametrize("bounds", [(1.0, 1.0), (0.0, -1.0), (-1.0, 1.0, 1.5), (-1.0, 1.0, -0.1)])
def test_a_bad_limit_is_refused_naming_its_joint(bounds):
    with pytest.raises(InvalidParameters) as err:
        simulation.Limit("crank", *bounds)
    assert err.value.name == "limit of crank"
