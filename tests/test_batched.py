"""The batched API (a leading sample axis) equals the single-sample API on every registered mechanism."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters, MethodUnavailable
from mechkit.bench.sampling import make_samples
from mechkit.catalog import registry
from mechkit.core.batch import BatchInverseDynamicsResult

#: Batched and per-sample results agree to this, relative to the largest value of the quantity (or 1).
TOL = 1e-13


def _close(batched: np.ndarray, single: np.ndarray) -> bool:
    return float(np.max(np.abs(batched - single), initial=0.0)) <= TOL * max(1.0, float(np.max(np.abs(single), initial=0.0)))


@pytest.fixture(scope="module", params=registry.names())
def case(request, load_cached):
    m = load_cached(request.param)
    return m, make_samples(m, 3)


def test_velocities_and_accelerations_batched(case):
    m, samples = case
    names = list(samples[0].input_names)
    Q = np.array([s.q for s in samples])
    R = np.array([s.rates for s in samples])
    Ac = np.array([s.accelerations for s in samples])
    V = m.velocities(Q, R, names)
    assert V.shape == (len(samples), m.model.nv)
    A = m.accelerations(Q, V, Ac, names)
    for i, s in enumerate(samples):
        v = m.velocities(s.q, s.rates, names)
        assert _close(V[i], v)
        assert _close(A[i], m.accelerations(s.q, v, s.accelerations, names))
    # a mapping of joint name -> per-sample values gives the same
    assert _close(m.velocities(Q, {n: R[:, k] for k, n in enumerate(names)}), V)


@pytest.mark.parametrize("determinacy", [True, False])
def test_inverse_dynamics_batched(case, determinacy):
    m, samples = case
    Q, V, A = (np.array([getattr(s, k) for s in samples]) for k in "qva")
    out = m.inverse_dynamics(Q, V, A, determinacy=determinacy)
    assert isinstance(out, BatchInverseDynamicsResult)
    nj = len(out.joint_names)
    assert out.efforts.shape == (len(samples), len(m.actuated)) and out.reactions.shape == (len(samples), nj, 6)
    assert (out.determinate is not None) == determinacy
    for i, s in enumerate(samples):
        one = m.inverse_dynamics(s.q, s.v, s.a, determinacy=determinacy)
        assert list(one.reactions) == list(out.joint_names)
        assert _close(out.efforts[i], np.array([one.efforts[j] for j in m.actuated]))
        wrenches = np.array([r.wrench for r in one.reactions.values()])
        assert _close(out.reactions[i], wrenches)
        assert _close(out.multipliers[i], one.multipliers)
        if determinacy:
            np.testing.assert_array_equal(out.determinate[i], np.array([r.determinate for r in one.reactions.values()]))
            assert out.efforts_determinate[i].tolist() == [one.efforts_determinate[j] for j in m.actuated]
        back = out.sample(i)
        assert _close(np.array([r.wrench for r in back.reactions.values()]), wrenches)
        assert [r.support for r in back.reactions.values()] == [r.support for r in one.reactions.values()]


@pytest.mark.parametrize("method", ["kkt", "proximal"])
def test_forward_dynamics_batched(case, method):
    m, samples = case
    Q, V, T = (np.array([getattr(s, k) for s in samples]) for k in ("q", "v", "tau"))
    try:
        out = m.forward_dynamics(Q, V, T, method)
    except MethodUnavailable:
        pytest.skip(f"{method} does not express this mechanism's cuts")
    for i, s in enumerate(samples):
        one = m.forward_dynamics(s.q, s.v, s.tau, method)
        assert _close(out.a[i], one.a)
        assert _close(out.constraint_force[i], one.constraint_force)


def test_batched_shapes_are_checked(load_cached):
    m = load_cached("four_bar")
    Q = np.array([m.home_q, m.home_q])
    with pytest.raises(InvalidParameters, match="v"):
        m.inverse_dynamics(Q, np.zeros((3, m.model.nv)), np.zeros((2, m.model.nv)))
    with pytest.raises(InvalidParameters, match="inputs"):
        m.velocities(Q, np.ones((2, 2)))
    with pytest.raises(InvalidParameters, match="q"):
        m.velocities(np.zeros((0, m.model.nq)), np.ones((0, 1)))
