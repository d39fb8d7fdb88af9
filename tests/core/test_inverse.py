"""Inverse dynamics (`mechkit.core.inverse`): the batch equals the single sample on every mechanism,
the gather reads Pinocchio fresh, regularity is judged as the kinematics judge it, empty batches keep
their shapes."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from tests_support import DISTANCES, singular_inputs

from mechkit import core
from mechkit.base.arguments import plain_state
from mechkit.base.exceptions import InvalidArgument, InvalidParameters, SingularConfiguration
from mechkit.bench.sampling import make_samples
from mechkit.catalog import registry
from mechkit.core import inverse
from mechkit.core.determinacy import system

#: Batched and per-sample results agree to this, relative to the largest value of the quantity (or 1).
TOL = 1e-13


def _close(batched: np.ndarray, single: np.ndarray) -> bool:
    return float(np.max(np.abs(batched - single), initial=0.0)) <= TOL * max(
        1.0, float(np.max(np.abs(single), initial=0.0))
    )


@pytest.fixture(scope="module", params=registry.names())
def case(request, load_cached):
    m = load_cached(request.param)
    return m, make_samples(m, 3)


@pytest.mark.parametrize("determinacy", [True, False])
def test_batch_equals_one_sample_at_a_time(case, determinacy):
    m, samples = case
    Q, V, A = (np.array([getattr(s, k) for s in samples]) for k in "qva")
    out = m.inverse_dynamics_batch(Q, V, A, determinacy=determinacy)
    assert isinstance(out, core.BatchInverseDynamicsResult)
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
        if determinacy:  # computed on first read: s_max / s_rank of [S^T, J^T], from its own SVD here
            pin.computeJointJacobians(m.model, m.closure_data.pin, s.q)
            G = m.closure_data.used_placements()[None]
            Jrows = m.closure_model.kernel.evaluate(G, m.closure_data.J[None], s.q[None])[1]
            sv = np.linalg.svd(system(m.closure_model, Jrows)[0], compute_uv=False)
            want = sv[0] / sv[int(np.sum(sv > 1e-9 * sv[0])) - 1]
            assert abs(one.condition - want) <= 1e-9 * want and abs(out.condition[i] - want) <= 1e-9 * want
        else:
            assert np.isnan(one.condition) and np.isnan(out.condition[i])


def test_batched_shapes_are_checked(load_cached):
    m = load_cached("four_bar")
    Q = np.array([m.home_q, m.home_q])
    with pytest.raises(InvalidParameters, match="v"):
        m.inverse_dynamics_batch(Q, np.zeros((3, m.model.nv)), np.zeros((2, m.model.nv)))
    with pytest.raises(InvalidParameters, match="input_rates"):
        m.velocities_batch(Q, np.ones((2, 2)))
    with pytest.raises(InvalidParameters, match="q"):
        m.velocities_batch(np.zeros((0, m.model.nq)), np.ones((0, 1)))


@pytest.mark.parametrize("name", registry.names())
def test_the_pass_reads_each_sample_fresh_from_pinocchio(name, load_cached):
    """The pass's held views of the data give, per sample, what a fresh data's Pinocchio calls give."""
    m = load_cached(name)
    model, cm = m.model, m.closure_model
    samples = make_samples(m, 3)
    Q, V, A = (np.array([getattr(s, k) for s in samples]) for k in "qva")
    P, J, tau, tree = inverse.inverse_pass(cm, cm.create_data(), Q, V, A, [None] * len(Q))
    for i in range(len(Q)):
        data = model.createData()
        pin.computeJointJacobians(model, data, Q[i])
        np.testing.assert_array_equal(P[i, :, :, :3], np.array([M.rotation for M in data.oMi.tolist()]))
        np.testing.assert_array_equal(P[i, :, :, 3], np.array([M.translation for M in data.oMi.tolist()]))
        np.testing.assert_array_equal(J[i], data.J)
        np.testing.assert_array_equal(tau[i], pin.rnea(model, data, Q[i], V[i], A[i]))
        world = [
            np.concatenate([M.rotation @ f.linear, M.rotation @ f.angular])
            for M, f in zip(data.oMi.tolist()[1:], data.f.tolist()[1:])
        ]
        np.testing.assert_allclose(tree[i], np.array(world), rtol=0, atol=1e-14 * max(1.0, np.abs(world).max()))


def test_regularity_is_judged_as_the_velocities_judge_it(load_cached):
    """Near the five-bar's singular inputs (both actuated, square passive block), inverse_dynamics raises
    exactly where `velocities` does, one sample or batched; with allow_singular it returns."""

    m = load_cached("five_bar")
    z = np.zeros(m.model.nv)
    regular = m.home_q
    for root, side in singular_inputs(m):
        for d in DISTANCES:
            q = m.assemble({"prox1": 2.6, "prox2": root + side * d}, guess=m.home_q)
            try:
                m.velocities(q, [1.0, 1.0])
                singular = False
            except SingularConfiguration:
                singular = True
            zeros = np.zeros((2, m.model.nv))
            for call, state in (
                (m.inverse_dynamics, (q, z, z)),
                (m.inverse_dynamics_batch, (np.array([regular, q]), zeros, zeros)),
            ):
                if singular:
                    with pytest.raises(SingularConfiguration):
                        call(*state)
                else:
                    call(*state)
            m.inverse_dynamics(q, z, z, allow_singular=True, determinacy=False)


@pytest.mark.parametrize("name", ["four_bar", "ten_bar", "deployable_9rr12uru"])
@pytest.mark.parametrize("determinacy", [True, False])
def test_zero_samples_give_empty_results(name, determinacy, load_cached):
    """A motion study may hand over no sample: every path keeps the (0, ...) shapes."""
    m = load_cached(name)
    cm, nv = m.closure_model, m.model.nv
    for distribution in core.DISTRIBUTIONS:
        out = core.inverse_dynamics_batch(
            cm,
            cm.create_data(),
            np.zeros((0, m.model.nq)),
            np.zeros((0, nv)),
            np.zeros((0, nv)),
            [],
            determinacy_test=determinacy,
            distribution=distribution,
            generic_rank=m.independent_rows,
        )
        assert out.efforts.shape == (0, len(m.actuated)) and out.reactions.shape == (0, len(cm.joint_names), 6)
        assert (out.determinate is None) != determinacy


@pytest.mark.parametrize("name", ["four_bar", "ten_bar", "deployable_9rr12uru"])
def test_multiplier_reactions_are_the_reactions_of_the_multipliers(name, load_cached):
    """At rest with no gravity, the reactions are what the multipliers alone transmit (`multiplier_reactions`)."""
    m = load_cached(name)
    cm = m.closure_model
    z = np.zeros(m.model.nv)
    model = m.model.copy()
    model.gravity.linear[:] = 0.0
    still = core.ClosureModel(model, m.closures, actuated=m.actuated)
    tau = np.zeros(m.model.nv)
    tau[[m.v_index(j) for j in m.actuated]] = 1.0  # efforts that the closures must hold
    out = core.inverse_dynamics(still, still.create_data(), m.home_q, z, z, None, -tau)
    loads = core.multiplier_reactions(cm, cm.create_data(), m.home_q, out.multipliers)
    tree = len(m.model.names) - 1
    np.testing.assert_allclose(out.reaction_values[tree:], loads[tree:], atol=1e-12 * max(1.0, np.abs(loads).max()))


def test_the_fast_path_gives_the_checked_path_numbers_and_still_refuses_bad_arrays(load_cached):
    """Plain float64 arrays skip the conversion (`arguments.plain_state`); lists go through it and give
    the same numbers; NaN, inf, another dtype or shape are refused by name, under the command line's
    np.errstate(all="raise") too, where large finite entries still pass."""
    m = load_cached("parallel_2t1r")
    s = make_samples(m, 1)[0]
    plain = m.inverse_dynamics(s.q, s.v, s.a, determinacy=False)
    listed = m.inverse_dynamics(s.q.tolist(), s.v.tolist(), s.a.tolist(), determinacy=False)
    np.testing.assert_array_equal(plain.reaction_values, listed.reaction_values)
    np.testing.assert_array_equal(plain.effort_values, listed.effort_values)
    with np.errstate(all="raise"):
        for bad in (np.nan, np.inf, -np.inf):
            a = s.a.copy()
            a[-1] = bad
            with pytest.raises(InvalidArgument, match="'a'"):
                m.inverse_dynamics(s.q, s.v, a)
        with pytest.raises(InvalidArgument, match="'v'"):
            m.inverse_dynamics(s.q, s.v[:-1], s.a)
        assert plain_state(s.q, s.v, np.full(m.model.nv, 1e300), m.model.nq, m.model.nv)
        one = m.inverse_dynamics(s.q.astype(np.float32).astype(np.float64), s.v, s.a, determinacy=False)
    assert np.all(np.isfinite(one.reaction_values))
