"""`mechkit.simulation.simulate`: a free motion's own checks (the energy balance, the closure), given torques
whose work is integrated with the motion, and bad options refused by name."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import scipy.integrate
import scipy.special

import mechkit
from mechkit import forces, simulation
from mechkit.base.exceptions import InvalidParameters


def test_conservative_energy_balance_and_closure(free):
    """No force but gravity: kinetic + potential stays constant to 1e-6 of the energy exchanged (measured
    2e-9), the loop stays closed to 1e-10 m (measured 1e-12), and nothing is supplied or dissipated."""
    assert free.energy_scale > 0.2  # J: the coupler swings through
    assert free.energy_error <= 1e-6 * free.energy_scale
    assert free.residual.max() <= 1e-10
    assert np.all(free.supplied == 0) and np.all(free.dissipated == 0)


def test_given_torque_supplies_the_integral_of_its_power(four_bar):
    """A constant 0.5 N m on the crank (a torque motor without envelope): the work supplied, integrated
    beside the motion, equals the quadrature of 0.5 x the crank's rate over the samples, and the balance closes."""
    run = four_bar.simulate(0.3, torques={"crank": 0.5}, reactions=False)
    assert run.element_names[-1] == "crank" and run.roles[-1] == "source"
    rate = run.motion.v[:, four_bar.v_index("crank")]
    quadrature = scipy.integrate.simpson(0.5 * rate, x=run.t)
    assert abs(run.supplied[-1]) > 1e-3
    assert run.supplied[-1] == pytest.approx(quadrature, rel=1e-5)
    assert run.energy_error <= 1e-6 * run.energy_scale and run.residual.max() <= 1e-10


@pytest.mark.parametrize(
    "options, name",
    [
        ({"duration": -1.0}, "duration"),
        ({"duration": float("nan")}, "duration"),
        ({"method": "Euler"}, "method"),
        ({"dt": 0.0}, "dt"),
    ],
)
def test_bad_options_are_refused_by_name(four_bar, options, name):
    duration = options.pop("duration", 0.1)
    with pytest.raises(InvalidParameters) as err:
        simulation.simulate(four_bar, duration, **options)
    assert err.value.name == name


def test_two_elements_of_one_name_are_refused(four_bar):
    a = forces.CoulombFriction(four_bar.model, {"crank": 0.1}, name="f")
    b = forces.CoulombFriction(four_bar.model, {"rocker": 0.1}, name="f")
    with pytest.raises(InvalidParameters) as err:
        simulation.simulate(four_bar, 0.1, forces=[a, b])
    assert err.value.name == "forces"


def test_an_unknown_latch_joint_is_refused(four_bar):
    with pytest.raises(InvalidParameters, match="nowhere"):
        simulation.simulate(four_bar, 0.1, latches=[simulation.Latch("nowhere", 0.0)])


PENDULUM = Path(__file__).resolve().parents[1] / "fixtures" / "iftomm" / "pendulum.urdf"
#: MuJoCo's model of the same pendulum (its body needs inertia > 1e-15: 1e-12 kg m^2 about the point mass).
PENDULUM_MJCF = """<mujoco><option gravity="0 0 -9.81" integrator="RK4" timestep="0.01"/><worldbody><body name="bob">
<joint name="pivot" type="hinge" axis="0 -1 0"/><inertial pos="1 0 0" mass="1" diaginertia="1e-12 1e-12 1e-12"/>
</body></worldbody></mujoco>"""


def _pendulum_error(t: np.ndarray, angle: np.ndarray) -> float:
    """Largest distance (m) of the bob from the exact solution released at rest from horizontal:
    theta(t) = 2 arcsin(k sn(K - w t | k^2)) from the downward vertical, k = sin(pi/4), w = sqrt(g / L)."""
    k2 = 0.5
    sn = scipy.special.ellipj(scipy.special.ellipk(k2) - np.sqrt(9.81) * t, k2)[0]
    theta = 2 * np.arcsin(np.sqrt(k2) * sn)
    return float(np.max(np.hypot(np.sin(theta) - np.cos(angle), -np.cos(theta) - np.sin(angle))))


@pytest.fixture(scope="module")
def pendulum():
    return mechkit.load(PENDULUM)


def test_iftomm_simple_pendulum_meets_high_precision_over_10_s(pendulum):
    """IFToMM benchmark "Simple pendulum" (tests/fixtures/iftomm/README.md): the default settings keep the bob
    within 1e-3 m (the library's high precision) of the exact elliptic-function solution; measured 1.0e-7."""
    run = pendulum.simulate(10.0, reactions=False)
    assert _pendulum_error(run.t, run.motion.q[:, 0]) < 1e-6 and run.energy_error < 1e-6


def test_the_pendulum_with_rk4_is_mujoco_s_rk4(pendulum):
    """The same method at the same step in both codes gives the same trajectory (to far below either's error
    against the exact solution, 1.2e-7 m at 0.01 s): an independent check of the RK4 stepper."""
    mujoco = pytest.importorskip("mujoco")
    run = pendulum.simulate(10.0, method="RK4", dt=0.01, reactions=False)
    model = mujoco.MjModel.from_xml_string(PENDULUM_MJCF)
    data = mujoco.MjData(model)
    theirs = [0.0]
    for _ in range(len(run.t) - 1):
        mujoco.mj_step(model, data)
        theirs.append(float(data.qpos[0]))
    assert np.max(np.abs(run.motion.q[:, 0] - theirs)) < 1e-9
    assert 1e-8 < _pendulum_error(run.t, run.motion.q[:, 0]) < 1e-6


@pytest.mark.slow
def test_iftomm_simple_pendulum_over_the_benchmark_s_2000_s(pendulum):
    run = pendulum.simulate(2000.0, method="DOP853", rtol=1e-10, atol=1e-12, reactions=False)
    assert _pendulum_error(run.t, run.motion.q[:, 0]) < 1e-3
