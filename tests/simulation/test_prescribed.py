"""`mechkit.simulation.prescribed`: prescribed joints. A sampled law's interpolation against the polynomial it
samples, drives and what a user may give; in simulation, a law followed exactly with the motor's work in
the balance, and the ten-bar's deployment (its motor laws as prescribed inputs, the R5 spring its own)
against the patent's Lagrange model, with the deployment's numbers."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit import simulation
from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import lagrange_deployment as tld
from mechkit.mechanisms.ten_bar import params as tp


class Sampled:
    """A sampled input law (`mechkit.motion.InputLaw`'s fields) of one joint: p(t) = t^5 - 2 t^3 + t at 4 instants."""

    names = ("crank",)
    t = np.array([0.0, 0.4, 1.1, 1.5])
    values = (t**5 - 2 * t**3 + t)[:, None]
    rates = (5 * t**4 - 6 * t**2 + 1)[:, None]
    accelerations = (20 * t**3 - 12 * t)[:, None]


def test_a_sampled_law_is_its_quintic_between_samples_and_held_outside():
    """A polynomial of degree 5 is what the piecewise quintic through values, rates and accelerations
    reproduces between the samples; before and after them the law holds its end value at rest."""
    law = simulation.law_of_samples(Sampled())
    for t in np.linspace(0.01, 1.49, 17):
        p, r, a = law(t)
        assert (p[0], r[0], a[0]) == pytest.approx(
            (t**5 - 2 * t**3 + t, 5 * t**4 - 6 * t**2 + 1, 20 * t**3 - 12 * t), rel=1e-9, abs=1e-12
        )
    p, r, a = law(2.0)
    assert p[0] == pytest.approx(Sampled.values[-1, 0]) and r[0] == 0.0 and a[0] == 0.0


class TwoJoints:
    """Two joints on one sampling: the first as `Sampled`, the second q(t) = 3 t^4 - t^2 (both degree <= 5)."""

    names = ("crank", "rocker")
    t = Sampled.t
    values = np.column_stack([Sampled.values[:, 0], 3 * t**4 - t**2])
    rates = np.column_stack([Sampled.rates[:, 0], 12 * t**3 - 2 * t])
    accelerations = np.column_stack([Sampled.accelerations[:, 0], 36 * t**2 - 2])


def test_a_law_of_several_joints_is_each_joints_polynomial_and_its_answers_are_copies():
    """Every joint of the law is evaluated at once (one Bernstein polynomial of both): each is its own
    polynomial; asking twice at one time (the simulator does within a step) gives equal, independent arrays."""
    law = simulation.law_of_samples(TwoJoints())
    for t in np.linspace(0.02, 1.48, 11):
        p, r, a = law(t)
        assert p[1] == pytest.approx(3 * t**4 - t**2, rel=1e-9, abs=1e-12)
        assert r[1] == pytest.approx(12 * t**3 - 2 * t, rel=1e-9, abs=1e-12)
        assert a[1] == pytest.approx(36 * t**2 - 2, rel=1e-9, abs=1e-12)
        assert p[0] == pytest.approx(t**5 - 2 * t**3 + t, rel=1e-9, abs=1e-12)
        p[:] = np.nan
        assert np.isfinite(law(t)[0]).all()


def test_drives_give_the_law_then_the_held_joints():
    """Prescribed joints first, held ones after at rest; holding and releasing return new drives."""
    law = lambda t: (np.array([t]), np.array([1.0]), np.array([0.0]))
    d = simulation.prescribed(law, ["crank"]).holding("rocker", 0.3)
    assert d.all == ("crank", "rocker")
    pos, rate, acc = d.at(2.0)
    assert pos.tolist() == [2.0, 0.3] and rate.tolist() == [1.0, 0.0] and acc.tolist() == [0.0, 0.0]
    assert d.releasing("rocker").all == ("crank",) and d.all == ("crank", "rocker")
    held = simulation.prescribed({"crank": 0.5})
    assert held.all == ("crank",) and held.at(7.0)[0].tolist() == [0.5]
    assert simulation.prescribed(Sampled()).names == ("crank",) and simulation.prescribed(None).all == ()


@pytest.mark.parametrize("inputs, names, name", [(lambda t: t, None, "input_names"), (3.0, None, "inputs")])
def test_what_cannot_be_a_law_is_refused_by_name(inputs, names, name):
    with pytest.raises(InvalidParameters) as err:
        simulation.prescribed(inputs, names)
    assert err.value.name == name
    with pytest.raises(InvalidParameters) as err:
        simulation.Drives(("crank",))
    assert err.value.name == "drives"


def test_prescribed_inputs_are_followed_and_their_work_balances(four_bar):
    """A crank driven by a law: it follows the law exactly, and the motor's work closes the balance."""
    law = lambda t: (
        np.array([0.6 + 0.5 * np.sin(3 * t)]),
        np.array([1.5 * np.cos(3 * t)]),
        np.array([-4.5 * np.sin(3 * t)]),
    )
    run = four_bar.simulate(1.0, inputs=law, input_names=["crank"])
    crank = run.motion.q[:, four_bar.q_index("crank")]
    assert np.allclose(crank, 0.6 + 0.5 * np.sin(3 * run.t), atol=1e-12)
    assert run.energy_error <= 1e-6 * run.energy_scale and np.ptp(run.supplied) > 0.01
    assert run.integrator["effort_check"] < 1e-9  # the inverse dynamics of every sample gives the same efforts


def test_a_sampled_law_starting_in_motion_starts_at_its_rate(four_bar):
    """A sampled law whose first sample moves: at the first and last instants the law gives the samples'
    own rates and accelerations (they were read as rest, and the run started the crank at 0 rad/s: its
    energy balance then missed the motor's first work), and the simulation starting there balances."""

    class Moving:
        names = ("crank",)
        t = np.linspace(0.0, 0.6, 7)
        values = (0.6 + 0.5 * np.sin(3 * t))[:, None]
        rates = (1.5 * np.cos(3 * t))[:, None]
        accelerations = (-4.5 * np.sin(3 * t))[:, None]

    law = simulation.law_of_samples(Moving())
    for edge in (0, -1):
        p, r, a = law(Moving.t[edge])
        assert (p[0], r[0], a[0]) == (Moving.values[edge, 0], Moving.rates[edge, 0], Moving.accelerations[edge, 0])
    run = four_bar.simulate(0.5, inputs=Moving(), reactions=False)
    assert run.motion.v[0, four_bar.v_index("crank")] == pytest.approx(1.5, abs=1e-12)
    assert run.energy_error <= 1e-6 * run.energy_scale and np.ptp(run.supplied) > 0.01


@pytest.fixture(scope="module")
def mech(load_cached):
    return load_cached("ten_bar")


def law(mech):
    return lambda t: tp.motor_law(mech.params, t)


def test_spring_release_against_the_lagrange_model(mech):
    """The first 0.5 s (the spring swings the rocker): the simulator's adaptive steps against the patent's
    Lagrange first kind (numpy, reference-point coordinates mapped to joints) at 5 ms fixed steps."""
    run = mech.simulate(0.5, inputs=law(mech), input_names=tp.MOTORS, reactions=False)
    lagrange = tld.LagrangeJointDeployment(mech.params)
    order = [mech.q_index(j) for j in td.JOINT_ORDER]
    ref = td.deploy(lagrange, mech.home_q[order], 0.005, 0.5)
    assert ref.t[-1] == pytest.approx(run.t[-1])
    assert np.max(np.abs(run.motion.q[-1, order] - ref.angles[-1])) < 1e-7
    assert abs(run.motion.q[-1, mech.q_index("R5")] - mech.home_q[mech.q_index("R5")]) > 0.5
    assert run.energy_error <= 1e-6 * run.energy_scale and run.residual.max() <= 1e-10


@pytest.mark.slow
def test_full_deployment_numbers(mech):
    """Stowed to deployed (20 s): the numbers of docs/mechanisms/ten_bar.md (motor torques R1 9.0..86.3 N m,
    R3 -0.75..18.9 N m, the rocker ending at -4.2 deg, both panels at 0)."""
    run = mech.simulate(mech.params.deploy_time, inputs=law(mech), input_names=tp.MOTORS)
    r1, r3 = run.motion.effort("R1"), run.motion.effort("R3")
    assert (round(r1.min(), 1), round(r1.max(), 1)) == (9.0, 86.3)
    assert (round(r3.min(), 2), round(r3.max(), 1)) == (-0.75, 18.9)
    assert round(float(np.degrees(run.motion.q[-1, mech.q_index("R5")])), 1) == -4.2
    assert np.allclose(run.motion.q[-1, [mech.q_index(j) for j in tp.MOTORS]], 0.0, atol=1e-12)
    assert run.residual.max() <= 1e-10 and run.energy_error <= 1e-6 * run.energy_scale
