"""The simulator's own checks and its agreement with independent methods: the energy balance, the closure
along the motion, a second integrator, the ten-bar's Lagrange model, MuJoCo, the static equilibrium,
impacts at limits and latches."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit import core, forces, simulation


@pytest.fixture(scope="module")
def four_bar(load_cached):
    return load_cached("four_bar")


@pytest.fixture(scope="module")
def free(four_bar):
    """The four-bar released at home under gravity, 1 s, conservative."""
    return four_bar.simulate(1.0)


def test_conservative_energy_balance_and_closure(free):
    """No force but gravity: kinetic + potential stays constant to 1e-6 of the energy exchanged (measured
    2e-9), the loop stays closed to 1e-10 m (measured 1e-12), and nothing is supplied or dissipated."""
    assert free.energy_scale > 0.2  # J: the coupler swings through
    assert free.energy_error <= 1e-6 * free.energy_scale
    assert free.residual.max() <= 1e-10
    assert np.all(free.supplied == 0) and np.all(free.dissipated == 0)


def test_a_second_integrator_agrees(four_bar, free):
    """DOP853 at a hundred times tighter tolerances follows the same motion."""
    other = four_bar.simulate(1.0, method="DOP853", rtol=1e-11, atol=1e-13, reactions=False)
    assert np.max(np.abs(other.motion.q[-1] - free.motion.q[-1])) < 1e-6
    assert other.energy_error <= 1e-8 * other.energy_scale


def test_reactions_balance_the_motion(four_bar, free):
    """Every sample's support reactions carry the weight and the centre of mass's acceleration."""
    from conftest import support_balance_error

    for k in (0, len(free.t) // 3, len(free.t) - 1):
        m = free.motion
        assert support_balance_error(four_bar, m.q[k], m.v[k], m.a[k]) < 1e-9


def test_against_mujoco_on_the_exported_mjcf(four_bar):
    """The same free motion in MuJoCo (exported MJCF, stiff equality settings, its RK4 at its step) and in
    the simulator at that step: the joint values agree to 1e-6 rad over 0.3 s (measured 4e-8), MuJoCo's
    loop opening by its soft constraint (measured 7e-9 m) and ours held to round-off."""
    pytest.importorskip("mujoco")
    from mechkit.bench.simulation_speed import simulation_speed

    row = simulation_speed(four_bar, 0.3)
    assert row.difference < 1e-6
    assert row.mechkit_closure <= 1e-12 < row.mujoco_closure < 1e-4


def test_released_passive_mechanism_settles_at_the_equilibrium(four_bar):
    """Released at home with a damper on the crank, the four-bar comes to rest where the static
    equilibrium solver says (a stable one), and all its energy went into the damper."""
    damper = forces.JointSprings(four_bar.model, [core.JointSpring("crank", damping=0.05)], "damper")
    run = four_bar.simulate(10.0, forces=[damper], reactions=False)
    eq = four_bar.equilibrium()
    assert eq.stable and eq.residual < 1e-9
    assert np.max(np.abs(run.motion.q[-1] - eq.q)) < 1e-6
    assert run.dissipated[-1] == pytest.approx(-(run.gravity[-1] - run.gravity[0]), rel=1e-6)
    assert run.energy_error <= 1e-6 * run.energy_scale


def test_equilibrium_with_a_held_input(load_cached):
    """The five-bar (two freedoms) with one crank held: the equilibrium keeps it, balances the other
    freedom, and a simulation from there with that crank held stays at rest."""
    five = load_cached("five_bar")
    held = five.actuated[0]
    eq = five.equilibrium({held: 0.4})
    assert eq.q[five.q_index(held)] == pytest.approx(0.4) and eq.residual < 1e-9 and len(eq.stiffness) == 1
    run = five.simulate(0.5, inputs={held: 0.4}, q0=eq.q, reactions=False)
    assert np.max(np.abs(run.motion.q[-1] - eq.q)) < (1e-6 if eq.stable else np.inf)


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
    assert np.all(np.isnan(run.motion.effort("crank")[~after])) and np.all(np.isfinite(run.motion.effort("crank")[after]))


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


def test_prescribed_inputs_are_followed_and_their_work_balances(four_bar):
    """A crank driven by a law: it follows the law exactly, and the motor's work closes the balance."""
    law = (lambda t: (np.array([0.6 + 0.5 * np.sin(3 * t)]), np.array([1.5 * np.cos(3 * t)]), np.array([-4.5 * np.sin(3 * t)])))
    run = four_bar.simulate(1.0, inputs=law, input_names=["crank"])
    crank = run.motion.q[:, four_bar.q_index("crank")]
    assert np.allclose(crank, 0.6 + 0.5 * np.sin(3 * run.t), atol=1e-12)
    assert run.energy_error <= 1e-6 * run.energy_scale and np.ptp(run.supplied) > 0.01
    assert run.integrator["effort_check"] < 1e-9  # the inverse dynamics of every sample gives the same efforts


def test_file_mechanism_falls_with_its_loops_closed():
    """Cassie (MuJoCo Menagerie: a free-flying pelvis, loops by equality connects) falling for 20 ms."""
    pytest.importorskip("mujoco")
    from pathlib import Path

    import mechkit

    path = Path(__file__).resolve().parents[1] / "fixtures/field/menagerie/agility_cassie/cassie.xml"
    mech = mechkit.load(path)
    run = mech.simulate(0.02, source=path, reactions=False)
    assert run.residual.max() <= 1e-10
    assert run.energy_error <= 1e-6 * run.energy_scale
