"""`mechkit.forces.point_to_point`: a strut between the ground and the four-bar's rocker. Its generalised
force (J^T f of its body wrenches) against central differences of its potential, its energy balance in a
simulation (spring: conservative; damper: dissipation = the quadrature of c L_dot^2 from the motion), its
force in the joint reactions (the moving assembly's ground reactions change by minus the strut's force),
and bad data refused by name."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
import scipy.integrate
import scipy.interpolate

from mechkit import forces, simulation
from mechkit.base.exceptions import InvalidParameters, SingularConfiguration

from .states import state

#: A strut from a ground point above the crank to the rocker's midpoint (m; ours).
GROUND_POINT, ROCKER_POINT = (0.1, 0.0, 0.15), (0.11, 0.0, 0.0)


def _strut(m, **data) -> forces.PointToPointForce:
    record = forces.PointToPoint("strut", "ground", "rocker_link", GROUND_POINT, ROCKER_POINT, **data)
    return forces.PointToPointForce(m.model, record)


def _length(m, q) -> float:
    data = m.model.createData()
    pin.framesForwardKinematics(m.model, data, q)
    a = data.oMf[m.model.getFrameId("ground")].act(np.array(GROUND_POINT))
    b = data.oMf[m.model.getFrameId("rocker_link")].act(np.array(ROCKER_POINT))
    return float(np.linalg.norm(b - a))


def test_generalized_force_is_minus_the_gradient_of_the_potential(four_bar):
    """Spring and gas force (conservative): J^T f of the wrenches equals -dV/dq by central differences in
    every tree coordinate to 1e-7 relative (the points do not lie on the loop: each coordinate moves them)."""
    m = four_bar
    strut = _strut(m, stiffness=300.0, free_length=0.12, force=4.0)
    s = state(m)
    tau = forces.generalized_of_wrenches(m.model, s.data, strut.load(s).wrenches)
    data, h = m.model.createData(), 1e-6
    gradient = np.zeros(m.model.nv)
    for i in range(m.model.nv):
        e = np.eye(m.model.nv)[i] * h
        plus, minus = pin.integrate(m.model, s.q, e), pin.integrate(m.model, s.q, -e)
        pin.forwardKinematics(m.model, data, plus)
        vp = strut.energy(m.model, data, plus)
        pin.forwardKinematics(m.model, data, minus)
        gradient[i] = (vp - strut.energy(m.model, data, minus)) / (2 * h)
    assert np.max(np.abs(tau)) > 1.0
    assert np.allclose(tau, -gradient, rtol=1e-7, atol=1e-7 * np.max(np.abs(tau)))
    stretch = _length(m, s.q) - 0.12
    assert strut.energy(m.model, s.data, s.q) == pytest.approx(150.0 * stretch**2 - 4.0 * stretch, rel=1e-12)


def test_spring_energy_is_conserved_and_damper_dissipates_its_power(four_bar):
    """1 s released at home: with the strut's spring, kinetic + gravity + spring potential stays constant to
    1e-7 of the energy exchanged (measured 5e-9); with a strut damper beside it, the dissipated energy equals
    the quadrature of c L_dot^2 over the samples (L_dot by differences of the recorded lengths' spline)."""
    m = four_bar
    spring = _strut(m, stiffness=200.0, free_length=0.1)
    run = m.simulate(1.0, forces=[spring], reactions=False, rtol=1e-9, atol=1e-11)
    assert np.ptp(run.potentials[:, -1]) > 0.3 and run.roles[-1] == "conservative"
    assert run.energy_error <= 1e-7 * run.energy_scale
    record = forces.PointToPoint("damper", "ground", "rocker_link", GROUND_POINT, ROCKER_POINT, damping=3.0)
    damper = forces.PointToPointForce(m.model, record)
    run = m.simulate(1.0, forces=[spring, damper], reactions=False, rtol=1e-9, atol=1e-11)
    assert run.energy_error <= 1e-7 * run.energy_scale
    lengths = np.array([_length(m, q) for q in run.motion.q])
    rate = scipy.interpolate.CubicSpline(run.t, lengths)(run.t, 1)
    quadrature = scipy.integrate.simpson(3.0 * rate**2, x=run.t)
    assert run.dissipated[-1] > 0.05
    assert run.dissipated[-1] == pytest.approx(quadrature, rel=1e-4)


def test_the_force_is_in_the_joint_reactions(four_bar):
    """Held still at crank 0.9 rad, the ground's reactions on crank and rocker change, with the strut, by
    minus the strut's force on the rocker (the moving assembly's force balance; the crank's motor gives a
    moment only), to 1e-9 N."""
    m = four_bar
    strut = _strut(m, stiffness=300.0, free_length=0.1, force=5.0)
    q = m.assemble([0.9])
    zero = np.zeros(m.model.nv)
    names = list(m.closure_model.joint_names)
    without = simulation.friction.inverse_dynamics(m, q, zero, zero, []).result.reaction_values
    with_ = simulation.friction.inverse_dynamics(m, q, zero, zero, [strut]).result.reaction_values
    change = sum(with_[names.index(j), :3] - without[names.index(j), :3] for j in ("crank", "rocker"))
    s = state(m, q, zero)
    _, _, u, length = strut.geometry(s.data)
    F = -300.0 * (length - 0.1) + 5.0
    assert abs(F) > 1.0
    assert np.allclose(change, -F * u, atol=1e-9)


def test_bad_data_is_refused_by_name(four_bar):
    with pytest.raises(InvalidParameters, match="stiffness"):
        forces.PointToPoint("s", "ground", "rocker_link", stiffness=-1.0)
    with pytest.raises(InvalidParameters, match="point_b"):
        forces.PointToPoint("s", "ground", "rocker_link", point_b=(0.0, 1.0))
    with pytest.raises(InvalidParameters, match="law"):
        forces.PointToPoint("s", "ground", "rocker_link", damping=1.0, law=lambda L, r, t: 0.0)
    with pytest.raises(InvalidParameters, match="frame_b"):
        forces.PointToPointForce(four_bar.model, forces.PointToPoint("s", "ground", "no_link"))
    same = forces.PointToPointForce(four_bar.model, forces.PointToPoint("s", "ground", "crank_link"))
    with pytest.raises(SingularConfiguration, match="coincide"):
        same.load(state(four_bar))


def test_a_law_is_a_source(four_bar):
    """A force law (N of the length, rate and time) supplies law x L_dot: its load's power, and the role."""
    m = four_bar
    law = lambda length, rate, t: 2.0 + 10.0 * length + t
    record = forces.PointToPoint("actuator", "ground", "rocker_link", GROUND_POINT, ROCKER_POINT, law=law)
    actuator = forces.PointToPointForce(m.model, record)
    s = state(m, t=0.5)
    load = actuator.load(s)
    tau = forces.generalized_of_wrenches(m.model, s.data, load.wrenches)
    assert actuator.role == "source"
    assert load.power == pytest.approx(float(tau @ s.v), rel=1e-10)
    assert abs(load.power) > 1e-3


def test_the_equilibrium_sees_the_strut(four_bar):
    """The static equilibrium under gravity and a stiff strut (a pose the strut moves far from the one gravity
    alone gives) is where the total potential's slope along the motion vanishes: central differences of
    gravity + strut potential over assembled poses, to 1e-6 J/rad."""
    m = four_bar
    strut = _strut(m, stiffness=300.0, free_length=0.3, force=1.0)  # pushes the rocker up: crank near 0.6 rad
    eq = m.equilibrium(elements=[strut])
    assert eq.residual < 1e-9
    assert np.max(np.abs(eq.q - m.equilibrium().q)) > 1.0
    data = m.model.createData()

    def potential(x):
        q = m.assemble([x], guess=eq.q)
        gravity = pin.computePotentialEnergy(m.model, data, q)
        return gravity + strut.energy(m.model, data, q)

    theta, h = eq.q[m.q_index("crank")], 1e-5
    assert abs((potential(theta + h) - potential(theta - h)) / (2 * h)) < 1e-6


def test_a_law_supplies_its_work_in_a_simulation(four_bar):
    """An actuator force law 5 sin(8 t) N along the strut's line for 0.5 s: the work supplied equals the
    quadrature of law x L_dot over the samples (1e-4) and the balance closes to 1e-7 of the energy exchanged."""
    m = four_bar
    law = lambda length, rate, t: 5.0 * np.sin(8.0 * t)
    record = forces.PointToPoint("actuator", "ground", "rocker_link", GROUND_POINT, ROCKER_POINT, law=law)
    run = m.simulate(0.5, forces=[forces.PointToPointForce(m.model, record)], reactions=False, rtol=1e-9, atol=1e-11)
    lengths = np.array([_length(m, q) for q in run.motion.q])
    rate = scipy.interpolate.CubicSpline(run.t, lengths)(run.t, 1)
    quadrature = scipy.integrate.simpson(5.0 * np.sin(8.0 * run.t) * rate, x=run.t)
    assert abs(run.supplied[-1]) > 1e-3
    assert run.supplied[-1] == pytest.approx(quadrature, rel=1e-4)
    assert run.energy_error <= 1e-7 * run.energy_scale
