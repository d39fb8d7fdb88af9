"""`mechkit.forces.cut_joints`: springs, dampers and friction on the four-bar's loop-cut pin C. The cut's
angle and rate against the closed form's relative angle of rocker and coupler; the spring's generalised
force along the motion against differences of its potential; a damper's dissipation in a simulation against
the quadrature of its power; and the viscous and Coulomb cases with every pin (A, B, D tree joints, C the
cut) against the hand-derived reduced model of the closed form (one freedom: the crank)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.integrate

from mechkit import core, forces, simulation
from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.four_bar.closed_form import motion

from .states import state

PINS = ("crank", "coupler", "rocker", "C")


def _cut_springs(m, *springs):
    return forces.CutJointSprings(m.model, m.closure_model.kernel.cuts, springs)


def test_cut_value_and_rate_are_the_closed_forms(four_bar):
    """At crank 0.9 rad turning at 1.5 rad/s: C's angle is the rocker's absolute angle minus the coupler's
    (wrapped) and its rate the difference of their rates, to 1e-9 (the closed form's links)."""
    m = four_bar
    s = state(m)
    joint = forces.cut_joints.cut_joints(m.closure_model.kernel.cuts, ["C"], "test")[0]
    exact = motion(m.params, [0.9], [1.5], [0.0]).links
    angle = math.remainder(exact["rocker"].angle - exact["coupler"].angle, 2 * math.pi)
    assert joint.value(s.data) == pytest.approx(angle, abs=1e-9)
    assert joint.rate(m.model, s.data) == pytest.approx(exact["rocker"].omega - exact["coupler"].omega, abs=1e-9)


def test_cut_spring_force_is_minus_the_potentials_slope_along_the_motion(four_bar):
    """The loop's one freedom: the spring's generalised force (J^T f of its moments) times dq/dtheta equals
    -dV/dtheta by central differences of V along the assembled motion, to 1e-7 relative."""
    m = four_bar
    spring = _cut_springs(m, core.JointSpring("C", 3.0, 0.5, preload=0.2))
    s = state(m, v=m.velocities(m.assemble([0.9]), [1.0]))
    tau = forces.generalized_of_wrenches(m.model, s.data, spring.load(s).wrenches)
    h = 1e-5
    energies = []
    for x in (0.9 + h, 0.9 - h):
        q = m.assemble([x], guess=s.q)
        energies.append(spring.energy(m.model, forces.ForceState.at(m.model, m.model.createData(), q, s.v).data, q))
    slope = (energies[0] - energies[1]) / (2 * h)
    assert abs(slope) > 0.1
    assert float(tau @ s.v) == pytest.approx(-slope, rel=1e-7)


def test_cut_damper_dissipates_the_integral_of_its_power(four_bar):
    """Released at home for 1 s with a damper on C: the dissipated energy equals the quadrature of
    c w_C^2, w_C = rocker rate - crank rate - coupler rate from the recorded velocities (planar, all axes -y),
    to 1e-4, and the balance closes to 1e-7 of the energy exchanged (measured 1e-9)."""
    m = four_bar
    damper = _cut_springs(m, core.JointSpring("C", damping=0.02))
    run = m.simulate(1.0, forces=[damper], reactions=False, rtol=1e-9, atol=1e-11)
    v = run.motion.v
    rate = v[:, m.v_index("rocker")] - v[:, m.v_index("crank")] - v[:, m.v_index("coupler")]
    quadrature = scipy.integrate.simpson(0.02 * rate**2, x=run.t)
    assert run.dissipated[-1] > 0.01
    assert run.dissipated[-1] == pytest.approx(quadrature, rel=1e-4)
    assert run.energy_error <= 1e-7 * run.energy_scale


def _reduced(m, theta: float, rate: float, damping: float, friction: float) -> float:
    """The crank's acceleration the pins' dampers and friction add: Q / m(theta), by the closed form. The
    reduced inertia m = sum of mass |v_com|^2 + I w^2 at unit crank rate; each pin's relative rate r_i at unit
    crank rate gives Q = -sum (c r_i^2 rate + F tanh(r_i rate / threshold) r_i)."""
    unit = motion(m.params, [theta], [1.0], [0.0])
    links = unit.links
    inertia = sum(
        link.bar.mass * float(link.com_velocity @ link.com_velocity) + link.bar.inertia_planar * link.omega**2
        for link in links.values()
    )
    Q = 0.0
    for joint in unit.joints:
        r = links[joint.child].omega - (links[joint.parent].omega if joint.parent else 0.0)
        Q -= damping * r**2 * rate + friction * math.tanh(r * rate / forces.SPEED_THRESHOLD) * r
    return Q / inertia


@pytest.mark.parametrize("damping, friction", [(0.03, 0.0), (0.0, 0.02), (0.03, 0.02)])
def test_every_pin_against_the_reduced_model(four_bar, damping, friction):
    """Viscous and Coulomb resistance on every pin, the cut pin C included: the crank's acceleration changes,
    against the same state without them, by the reduced model's Q / m(theta) to 1e-8 relative, at two crank
    angles and rates (Coulomb at rates well above its threshold and one within it)."""
    m = four_bar
    cuts = m.closure_model.kernel.cuts
    elements = []
    if damping:
        tree = [core.JointSpring(j, damping=damping) for j in PINS[:3]]
        elements += [forces.JointSprings(m.model, tree), _cut_springs(m, core.JointSpring("C", damping=damping))]
    if friction:
        elements += [
            forces.CoulombFriction(m.model, {j: friction for j in PINS[:3]}),
            forces.CutJointFriction(m.model, cuts, {"C": friction}),
        ]
    bare = simulation.MechanismSystem(m, [], simulation.Drives(), "kkt")
    loaded = simulation.MechanismSystem(m, elements, simulation.Drives(), "kkt")
    k = m.v_index("crank")
    for theta, rate in ((0.9, 2.0), (2.6, -0.7), (4.0, 0.004)):
        q = m.assemble([theta], guess=motion(m.params, [theta], [rate], [0.0]).q)  # the closed form's branch
        v = m.velocities(q, [rate])
        change = loaded.evaluate(0.0, q, v).a[k] - bare.evaluate(0.0, q, v).a[k]
        expected = _reduced(m, theta, rate, damping, friction)
        assert abs(expected) > 1e-3
        assert change == pytest.approx(expected, rel=1e-8)


def test_bad_cut_joints_are_refused_by_name(four_bar):
    cuts = four_bar.closure_model.kernel.cuts
    with pytest.raises(InvalidParameters, match="no such cut joint"):
        forces.CutJointSprings(four_bar.model, cuts, [core.JointSpring("crank", 1.0)])
    with pytest.raises(InvalidParameters, match="threshold"):
        forces.CutJointFriction(four_bar.model, cuts, {"C": 0.1}, threshold=0.0)
    with pytest.raises(InvalidParameters, match="friction on C"):
        forces.CutJointFriction(four_bar.model, cuts, {"C": -0.1})


def test_a_cut_joint_effort_supplies_effort_times_rate(four_bar):
    """A 0.3 N m torque on C (a function of time, at t = 0.5 s: 0.3): its power is 0.3 x C's rate, and equals
    the power of its generalised force J^T f (the wrenches' work on the tree's velocities), to 1e-12."""
    m = four_bar
    effort = forces.CutJointEffort(m.model, m.closure_model.kernel.cuts, "C", lambda t: 0.6 * t)
    s = state(m, t=0.5)
    load = effort.load(s)
    exact = motion(m.params, [0.9], [1.5], [0.0]).links
    assert effort.role == "source" and effort.name == "effort on C"
    assert load.power == pytest.approx(0.3 * (exact["rocker"].omega - exact["coupler"].omega), rel=1e-9)
    tau = forces.generalized_of_wrenches(m.model, s.data, load.wrenches)
    assert float(tau @ s.v) == pytest.approx(load.power, rel=1e-12)


def test_the_tree_joint_elements_point_to_the_cut_joint_ones(four_bar):
    """A spring on the cut pin C given to `JointSprings` without the cuts, or friction on it to
    `CoulombFriction`, is refused, naming what takes it."""
    with pytest.raises(InvalidParameters, match="pass the cuts"):
        forces.JointSprings(four_bar.model, [core.JointSpring("C", 1.0)])
    with pytest.raises(InvalidParameters, match="CutJointFriction"):
        forces.CoulombFriction(four_bar.model, {"C": 0.1})


def test_joint_springs_with_the_cuts_take_the_cut_joints_springs(four_bar):
    """`JointSprings` given the cuts: springs on a tree joint and on C in one element. Its batch generalised
    forces and potential over two samples equal, sample by sample, its load (J^T f of the cut's wrenches
    added) and `energy`, and the sum of a tree-only `JointSprings` and a `CutJointSprings` (1e-12)."""
    m = four_bar
    cuts = m.closure_model.kernel.cuts
    tree, cut = core.JointSpring("rocker", 2.0, 1.0, damping=0.1), core.JointSpring("C", 3.0, 0.5, 0.2, 0.05)
    both = forces.JointSprings(m.model, [tree, cut], cuts=cuts)
    apart = [forces.JointSprings(m.model, [tree]), forces.CutJointSprings(m.model, cuts, [cut])]
    qs = [m.assemble([x]) for x in (0.9, 1.7)]
    vs = [m.velocities(q, [r]) for q, r in zip(qs, (1.5, -0.8))]
    forces_batch, potential_batch = both.forces(np.array(qs), np.array(vs)), both.potential(np.array(qs))
    for k, (q, v) in enumerate(zip(qs, vs)):
        s = state(m, q, v)
        loads = [both.load(s)] + [e.load(s) for e in apart]
        tau = [
            (x.generalized if x.generalized is not None else 0.0)
            + (forces.generalized_of_wrenches(m.model, s.data, x.wrenches) if x.wrenches is not None else 0.0)
            for x in loads
        ]
        assert np.allclose(forces_batch[k], tau[0], atol=1e-12) and np.allclose(tau[0], tau[1] + tau[2], atol=1e-12)
        assert loads[0].power == pytest.approx(loads[1].power + loads[2].power, rel=1e-12)
        energy = both.energy(m.model, s.data, q)
        assert potential_batch[k] == pytest.approx(energy, rel=1e-12)
        assert energy == pytest.approx(sum(e.energy(m.model, s.data, q) for e in apart), rel=1e-12)
        assert abs(float(tau[0] @ v)) > 1e-3
