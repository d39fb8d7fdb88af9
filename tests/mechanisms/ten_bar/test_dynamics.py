"""`mechkit.mechanisms.ten_bar.dynamics`: constrained ABA against the Lagrange first kind, the
deployment two ways, fourth-order convergence, and the passive DOF decided by the dynamics."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechkit.mechanisms.ten_bar import checks as tc
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar import lagrange_model as lm
from mechkit.mechanisms.ten_bar import limits as tl
from mechkit.mechanisms.ten_bar import params as tp
from mechkit.mechanisms.ten_bar.lagrange_deployment import LagrangeDeployment, LagrangeJointDeployment

from .states import mid_state


@pytest.fixture(scope="module")
def stretch(mech):
    """The first 0.1 s of the deployment (spring release) by both dynamics routes, dt = 5 ms."""
    pin_run = td.PinocchioDeployment(mech)
    lag_run = LagrangeJointDeployment(mech.params)
    a = td.deploy(pin_run, mech.home_q, 0.005, 0.1)
    b = td.deploy(lag_run, pin_run.joint_angles(mech.home_q), 0.005, 0.1)
    return a, b


# ------------------------------------------------------------------ dynamics two ways
@pytest.mark.parametrize("rates", [(0.0, 0.0, 0.0), (0.05, -0.1, 0.2), (-0.3, 0.4, -2.0)])
def test_constrained_aba_equals_the_lagrange_first_kind(mech, rates):
    t, q, v = mid_state(mech, rates)
    a, u, power = td.PinocchioDeployment(mech).rhs(t, q, v)
    lag = LagrangeJointDeployment(mech.params)
    aL, uL, powerL = lag.rhs(
        t,
        lag.joint_angles(q[[mech.q_index(j) for j in td.JOINT_ORDER]]),
        v[[mech.v_index(j) for j in td.JOINT_ORDER]],
    )
    order = [mech.v_index(j) for j in td.JOINT_ORDER]
    assert np.max(np.abs(a[order] - aL)) < 1e-9 * max(1.0, np.max(np.abs(aL)))
    assert np.allclose(u, uL, rtol=1e-10, atol=1e-10) and power == pytest.approx(powerL, rel=1e-10, abs=1e-12)


def test_deployment_stretch_two_ways(stretch):
    a, b = stretch
    assert max(a.residual.max(), b.residual.max()) < 1e-9
    assert np.max(np.abs(a.angles - b.angles)) < 1e-8
    assert np.allclose(a.torques, b.torques, rtol=1e-8, atol=1e-8)
    assert a.energy_error < 1e-3 and b.energy_error < 1e-3  # J, against ~60 J of energy exchanged
    assert abs(a.angles[-1, 5] - a.angles[0, 5]) > 0.5  # the spring has swung the rocker


def test_lagrange_in_its_own_coordinates_converges_at_fourth_order(mech):
    pin_run, lag_run = td.PinocchioDeployment(mech), LagrangeDeployment(mech.params)
    qL = lm.lagrange_coordinates(mech.params, geo.stowed_pose(mech.params))
    diffs = []
    for dt in (0.02, 0.01):
        a = td.deploy(pin_run, mech.home_q, dt, 0.2)
        b = td.deploy(lag_run, qL, dt, 0.2)
        diffs.append(np.max(np.abs(a.angles - b.angles)))
    assert math.log2(diffs[0] / diffs[1]) > 3.5


def test_the_dynamics_decides_the_passive_dof(mech, load_cached):
    stiff = load_cached("ten_bar", spring_stiffness=8.0, spring_preload=10.8)
    a = td.deploy(td.PinocchioDeployment(mech), mech.home_q, 0.01, 0.2)
    b = td.deploy(td.PinocchioDeployment(stiff), stiff.home_q, 0.01, 0.2)
    motors = [td.JOINT_ORDER.index(m) for m in tp.MOTORS]
    assert np.allclose(a.angles[:, motors], b.angles[:, motors], atol=1e-12)
    assert abs(a.angles[-1, 5] - b.angles[-1, 5]) > 0.05


@pytest.mark.slow
def test_full_deployment(mech):
    pin_run = td.PinocchioDeployment(mech)
    a = td.deploy(pin_run, mech.home_q, 0.005)
    b = td.deploy(LagrangeJointDeployment(mech.params), pin_run.joint_angles(mech.home_q), 0.005)
    assert a.residual.max() < 1e-9 and b.residual.max() < 1e-9
    assert np.max(np.abs(a.angles - b.angles)) < 1e-8
    motors = [td.JOINT_ORDER.index(m) for m in tp.MOTORS]
    assert np.allclose(a.angles[-1, motors], [tp.DEPLOYED[m] for m in tp.MOTORS], atol=1e-12)
    margins = tl.loop_margins(mech.params, a.angles[::10])
    assert min(m.min() for m in margins.values()) > 0.6
    for k in (len(a.t) // 4, len(a.t) // 2, 3 * len(a.t) // 4):
        assert tc.reaction_disagreement(tc.reactions_three_ways(mech, a.t[k], a.q[k], a.v[k])) < 1e-8
