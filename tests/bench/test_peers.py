"""Peers on the same mechanism: their answers approach ours as their constraints stiffen."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import MethodUnavailable
from mechkit.bench import peers

pytest.importorskip("mujoco")


def _rel(a, b) -> float:
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


@pytest.mark.parametrize("name", ["four_bar", "rocket_gimbal"])
def test_mujoco_at_rest_converges_to_ours_as_it_stiffens(name, load_cached):
    """At rest under gravity, MuJoCo's soft closure is visibly off by default and 100x closer when stiff.

    (four_bar: 1e-2 -> 1e-5; rocket_gimbal, whose true accelerations at rest are small beside the
    gravity load the closure carries: 16 -> 1.5e-2.)
    """
    m = load_cached(name)
    zero = np.zeros(m.model.nv)
    ours = m.forward_dynamics(m.home_q, zero, zero, "kkt").a
    default = _rel(peers.MujocoPeer(m).forward(m.home_q, zero, zero), ours)
    stiff = _rel(peers.MujocoPeer(m, stiff=True).forward(m.home_q, zero, zero), ours)
    assert default > 1e-3
    assert stiff < min(default / 100, 0.05)


def test_mujoco_inverse_split_gives_our_efforts(load_cached):
    """mj_inverse + the least-squares split on MuJoCo's constraint Jacobian: the same efforts as the core."""
    m = load_cached("five_bar")
    q = m.home_q
    v = m.velocities(q, [0.4, -0.3])
    a = m.accelerations(q, v, [1.0, 0.5])
    ours = m.inverse_dynamics(q, v, a, determinacy=False).efforts
    theirs = peers.MujocoPeer(m).inverse(q, v, a)
    for joint, u in ours.items():
        assert theirs[joint] == pytest.approx(u, rel=1e-9, abs=1e-12)


def test_drake_at_rest_agrees_to_its_step_error(load_cached):
    """Drake's one SAP step from rest: (v_next - v)/dt matches our accelerations to O(dt)."""
    m = load_cached("four_bar")
    try:
        drake = peers.DrakePeer(m)
    except MethodUnavailable as err:
        assert "pip install drake" in str(err)
        pytest.skip("Drake not installed")
    zero = np.zeros(m.model.nv)
    ours = m.forward_dynamics(m.home_q, zero, zero, "kkt").a
    assert _rel(drake.forward(m.home_q, zero, zero), ours) < 1e-2


@pytest.mark.parametrize("name", ["four_bar", "parallel_2t1r", "spherical_2dof"])
def test_drake_bench_row_gives_finite_accelerations_near_ours(name, load_cached):
    """The bench's Drake row on the bench's samples: finite accelerations off ours by SAP's one-step error
    (measured: 4e-2 of 1.6e2 rad/s^2 on the four-bar, 1.1 of 80 on the 2T1R; spherical_2dof: its cuts keep
    the alignment rows, mapped to the ball point along the axis alone), below MuJoCo's default soft
    closure's (1.9, 2.5)."""
    pytest.importorskip("pydrake", reason="Drake not installed: pip install 'mechkit[peers]'")
    from mechkit.bench.sampling import make_samples

    m = load_cached(name)
    methods, notes = peers.peer_methods(m)
    drake = [meth for meth in methods if meth.name.startswith("Drake")]
    assert len(drake) == 1 and drake[0].quantity == "forward_dynamics", notes
    for s in make_samples(m, 2):
        a = drake[0].run(m, s)
        ours = m.forward_dynamics(s.q, s.v, s.tau, "kkt").a
        assert a.shape == ours.shape and np.all(np.isfinite(a))
        err = np.max(np.abs(a - ours))
        assert err < 0.03 * np.max(np.abs(ours))
        assert err < np.max(np.abs(peers.MujocoPeer(m).forward(s.q, s.v, s.tau) - ours))
