"""`mechkit.simulation.system`: the equations of motion a simulation integrates: computed-torque drives
against the core's inverse dynamics, the energies against Pinocchio's, and the fixed point of joint
friction and reactions (dissipation against the integral of its power, the energy balance with it)."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit import core, forces, simulation
from mechkit.base.exceptions import InvalidParameters

from .pins import friction


def _moving(m):
    q = m.assemble([0.9])
    return q, m.velocities(q, [2.0])


def test_computed_torque_drives_follow_their_law_with_the_inverse_dynamics_effort(four_bar):
    """The crank driven by a law: the accelerations keep the closure (J a + J' v = 0, from the core's
    acceleration of the input), the crank's acceleration is the law's, and the drive's effort is the one
    the core's inverse dynamics gives for that motion (with the springs the element list carries)."""
    m = four_bar
    law = lambda t: (np.array([0.9]), np.array([2.0]), np.array([-3.0 + t]))
    spring = forces.JointSprings(m.model, [core.JointSpring("rocker", 1.5, 0.2)])
    system = simulation.MechanismSystem(m, [spring], simulation.Drives(("crank",), law), "kkt")
    q, v = _moving(m)
    ev = system.evaluate(0.5, q, v)
    assert ev.a[m.v_index("crank")] == pytest.approx(-2.5, rel=1e-10)
    expected = m.accelerations(q, v, [-2.5])
    assert np.allclose(ev.a, expected, atol=1e-9)
    tau = spring.load(forces.ForceState.at(m.model, m.model.createData(), q, v)).generalized
    cm, cd = system.driven()
    reference = core.inverse_dynamics(cm, cd, q, v, expected, None, tau, determinacy_test=False)
    assert ev.efforts[0] == pytest.approx(float(reference.effort_values[0]), rel=1e-9)
    assert ev.powers[0] == pytest.approx(0.0) and ev.reactions is None and ev.iterations == 0


def test_energies_are_pinocchios(four_bar):
    """The kinetic energy is v^T M v / 2 and the gravity potential Pinocchio's, each element's potential after it."""
    m = four_bar
    spring = forces.JointSprings(m.model, [core.JointSpring("rocker", 1.5, 0.2)])
    system = simulation.MechanismSystem(m, [spring], simulation.Drives())
    q, v = _moving(m)
    M = pin.crba(m.model, m.model.createData(), q)
    M = np.triu(M) + np.triu(M, 1).T
    assert system.kinetic(q, v) == pytest.approx(0.5 * v @ M @ v, rel=1e-12)
    rocker = q[m.q_index("rocker")]
    potentials = system.potentials(q)
    assert potentials[0] == pytest.approx(pin.computePotentialEnergy(m.model, m.model.createData(), q), rel=1e-12)
    assert potentials[1] == pytest.approx(0.5 * 1.5 * (rocker - 0.2) ** 2, rel=1e-12)


def test_friction_fixed_point_is_the_friction_of_its_own_reactions(four_bar):
    """With friction from the reactions: the friction loads of the evaluation are those the element gives
    for the reactions the evaluation reports (the fixed point), and the reactions are the core's inverse
    dynamics at the accelerations found under those loads."""
    m = four_bar
    element = friction(m)
    system = simulation.MechanismSystem(m, [element], simulation.Drives(), "kkt")
    q, v = _moving(m)
    ev = system.evaluate(0.0, q, v)
    assert ev.iterations >= 2 and ev.reactions is not None
    state = forces.ForceState.at(m.model, m.model.createData(), q, v)
    state.reactions = ev.reactions
    load = element.load(state)
    assert np.allclose(load.generalized, ev.generalized, rtol=1e-9, atol=1e-12)
    assert np.allclose(load.wrenches, ev.wrenches, rtol=1e-9, atol=1e-12)
    again = system.reactions(q, v, ev.a, ev.generalized, ev.wrenches).reaction_values
    assert np.allclose(again, ev.reactions, rtol=1e-8, atol=1e-10)
    assert ev.powers[0] == pytest.approx(load.power, rel=1e-9) and ev.powers[0] < 0


def test_friction_that_locks_stops_the_evaluation_by_name(four_bar):
    m = four_bar
    cm = m.closure_model
    locking = forces.ReactionFriction(
        m.model, cm.joint_names, cm.kernel.cuts, {j: forces.PinFriction(80.0, 0.05) for j in cm.joint_names}
    )
    system = simulation.MechanismSystem(m, [locking], simulation.Drives(), "kkt")
    q, v = _moving(m)
    with pytest.raises(forces.FrictionLocks, match="t = 0.25 s"):
        system.evaluate(0.25, q, v)


@pytest.fixture(scope="module")
def rubbing(four_bar):
    """The four-bar released at home with friction at every pin, 0.4 s."""
    return four_bar.simulate(0.4, forces=[friction(four_bar)])


def test_friction_dissipates_what_its_power_integrates_to(rubbing):
    """The dissipated energy integrated with the motion equals the integral of the recorded friction power
    (Simpson's rule over the samples; the difference is that quadrature's error, measured 2e-7 relative)."""
    import scipy.integrate

    dissipated = rubbing.dissipated[-1]
    quadrature = -scipy.integrate.simpson(rubbing.friction_power, x=rubbing.t)
    assert dissipated > 1e-3
    assert quadrature == pytest.approx(dissipated, rel=1e-5)


def test_energy_balance_with_friction(rubbing):
    """Kinetic + potential + dissipated stays constant to the integrator's tolerance, the loop closed."""
    assert rubbing.energy_error <= 1e-7 * rubbing.energy_scale
    assert rubbing.residual.max() <= 1e-10
    assert np.all(np.diff(rubbing.dissipated) >= -1e-12)  # friction never gives energy back


def test_corrected_friction_against_the_converged_fixed_point(four_bar):
    """Scheme "corrected" (the previous evaluation's friction, corrected from its own reactions) against the
    fixed point iterated to 1e-11: the four-bar released with friction at every pin, RK4 at 2 ms over 0.1 s:
    the motions agree to 1e-6 rad (measured 1.7e-7; RK4's own error at that step is about 1e-4 rad);
    evaluated in turn at the samples of that motion (2 ms apart, farther than a step's stages), its
    accelerations agree to 2e-5 of their size (measured 8.3e-6) with at most three inverse dynamics an
    evaluation where the fixed point takes six or seven."""
    m = four_bar
    runs = {
        s: m.simulate(0.1, forces=[friction(m)], friction_scheme=s, reactions=False, limits=None, method="RK4", dt=2e-3)
        for s in ("fixed point", "corrected")
    }
    exact = runs["fixed point"]
    assert np.max(np.abs(exact.motion.q - runs["corrected"].motion.q)) < 1e-6
    fixed = simulation.MechanismSystem(m, [friction(m)], simulation.Drives(), "kkt", friction_scheme="fixed point")
    corrected = simulation.MechanismSystem(m, [friction(m)], simulation.Drives(), "kkt", friction_scheme="corrected")
    for k, (q, v) in enumerate(zip(exact.motion.q[5:], exact.motion.v[5:])):
        x, y = fixed.evaluate(0.0, q, v), corrected.evaluate(0.0, q, v)
        assert np.max(np.abs(x.a - y.a)) <= 2e-5 * np.max(np.abs(x.a))
        assert x.iterations >= 5 and (k == 0 or y.iterations <= 3)


def test_an_unknown_friction_scheme_is_refused_by_name(four_bar):
    with pytest.raises(InvalidParameters) as err:
        simulation.MechanismSystem(four_bar, [], simulation.Drives(), friction_scheme="implicit")
    assert err.value.name == "friction_scheme"


def test_friction_from_the_proximal_multipliers_against_the_inverse_dynamics_on_mechkit_rows(four_bar):
    """Friction from the reactions read off the proximal solve's multipliers (one RNEA pass) and friction
    from the core's inverse dynamics under "kkt" (an independent solve) reach the same fixed point: the
    accelerations agree to the proximal solve's accuracy, the reactions to 1e-8 of the largest."""
    m = four_bar
    q, v = _moving(m)
    evs = [
        simulation.MechanismSystem(m, [friction(m)], simulation.Drives(), method).evaluate(0.0, q, v)
        for method in ("proximal", "kkt")
    ]
    assert np.max(np.abs(evs[0].a - evs[1].a)) <= 1e-8 * np.max(np.abs(evs[1].a))
    assert np.max(np.abs(evs[0].reactions - evs[1].reactions)) <= 1e-8 * np.max(np.abs(evs[1].reactions))
    assert np.max(np.abs(evs[0].generalized - evs[1].generalized)) <= 1e-8 * np.max(np.abs(evs[1].generalized))
