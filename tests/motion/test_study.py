"""`mechkit.motion.study`: the study against per-sample inverse dynamics and the power balance."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit import motion
from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_RATES


def test_study_equals_per_sample_inverse_dynamics(two_t1r):
    mech, r = two_t1r
    for i in range(len(r.t)):
        closure = np.abs(mech.closure_residual(r.q[i])).max()
        assert closure < 1e-10
        ref = mech.inverse_dynamics(r.q[i], r.v[i], r.a[i])
        assert np.allclose(r.efforts[i], [ref.efforts[j] for j in r.effort_names], rtol=1e-12, atol=1e-12)
        for j, joint in enumerate(r.joints):
            assert np.allclose(r.reactions[i, j], ref.reactions[joint].wrench, rtol=1e-12, atol=1e-10)
            assert np.array_equal(r.determinate[i, j], ref.reactions[joint].determinate)


@pytest.mark.parametrize("case", ["two_t1r", "four_bar"])
def test_inputs_and_power_balance(case, request):
    """The drives' power u . input rates equals v . (M a + nle) (J v = 0: the closures do no work),
    and the inputs follow the law."""
    mech, r = request.getfixturevalue(case)
    for i in range(len(r.t)):
        rates = [r.v[i, mech.v_index(j)] for j in r.effort_names]
        power = float(np.dot(r.efforts[i], rates))
        rate_of_energy = float(r.v[i] @ pin.rnea(mech.model, mech.data, r.q[i], r.v[i], r.a[i]))
        assert power == pytest.approx(rate_of_energy, rel=1e-9, abs=1e-9)
    if case == "two_t1r":
        assert np.allclose(r.v[:, [mech.v_index(j) for j in ("R11", "R21", "R31")]], MOTION_RATES, atol=1e-14)


def test_passive_input_effort_closes_the_power_balance(load_cached):
    """Ten-bar: R5 is an input of the law without an actuator; its effort is what its spring does not give:
    efforts and spring together deliver the power the motion takes."""
    mech = load_cached("ten_bar")
    home = [mech.home_q[mech.q_index(j)] for j in ("R1", "R3", "R5")]

    def law(t):
        return np.array(home) + np.array([-0.05, 0.05, 0.02]) * np.sin(t)

    r = motion.study(mech, motion.from_callable(mech, law, np.linspace(0.0, 1.0, 6)))
    assert r.effort_names == ("R1", "R3", "R5") and r.actuated == ("R1", "R3")
    for i in range(len(r.t)):
        power = r.efforts[i] @ r.v[i, [mech.v_index(j) for j in r.effort_names]] + r.v[i] @ mech.passive_forces(
            r.q[i], r.v[i]
        )
        assert power == pytest.approx(r.v[i] @ pin.rnea(mech.model, mech.data, r.q[i], r.v[i], r.a[i]), rel=1e-9)


def test_ten_bar_efforts_equal_the_deployment_dynamics(load_cached):
    """Along the ten-bar's deployment (constrained forward dynamics, its transient included), the study's
    efforts are the motor torques that realised the motion, and at the spring hinge R5 the spring and
    damper torque: forward and inverse dynamics agree."""
    from mechkit.mechanisms.ten_bar import dynamics as td

    mech = load_cached("ten_bar")
    system = td.PinocchioDeployment(mech)
    trajectory = td.deploy(system, mech.home_q, 0.02, t_end=0.3)
    names = motion.default_inputs(mech)
    idx = [mech.v_index(j) for j in names]
    states = [system.rhs(t, q, v) for t, q, v in zip(trajectory.t, trajectory.q, trajectory.v)]
    acc = np.array([s[0] for s in states])
    law = motion.from_arrays(
        mech, trajectory.t, trajectory.q[:, idx], trajectory.v[:, idx], acc[:, idx], names=names, guesses=trajectory.q
    )
    r = motion.study(mech, law)
    assert np.allclose(r.v, trajectory.v, atol=1e-12) and np.allclose(r.a, acc, atol=1e-10)
    # the R5 input's driven force is what the spring does not supply: nothing, the motion is the spring's own
    expected = np.column_stack([np.array([s[1] for s in states]), np.zeros(len(states))])
    assert np.allclose(r.efforts, expected, rtol=1e-11, atol=1e-11 * np.abs(expected).max())
