"""The ten-bar's deployment as one use of the simulator: its motor laws as prescribed inputs, the R5
spring its own; against the patent's Lagrange model, and the deployment's numbers."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import lagrange_deployment as tld
from mechkit.mechanisms.ten_bar import params as tp


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
