"""The solutions of J a + gamma = 0 (`mechkit.core.null_space`): the LU partition certifies the SVD's
decisions and gives its accelerations, and leaves a state with no rigid answer to the SVD, which
refuses it."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit import core
from mechkit.base.exceptions import InconsistentMotion
from mechkit.bench.sampling import make_samples
from mechkit.catalog import registry
from mechkit.core import forward, null_space

from .no_rigid_answer import inconsistent_state


@pytest.mark.parametrize("name", registry.names())
def test_the_partitioned_null_space_is_certified_and_gives_the_svd_numbers(name, load_cached):
    """At the bench's states the null-space method's LU partition certifies the SVD's rank and
    consistency decisions (`null_space.partitioned_null_space` returns), and its a_p, N give the
    accelerations the SVD's orthonormal basis gives."""
    m = load_cached(name)
    cm, cd = m.closure_model, m.closure_model.create_data()
    for s in make_samples(m, 3):
        J, gamma, _ = forward._rows_and_drift(cm, cd, s.q, s.v, None)
        split = null_space.partitioned_null_space(cd, J, gamma)
        assert split is not None
        a_p, N = split
        scale = np.abs(J).max() * max(np.abs(a_p).max(), 1.0) + np.abs(gamma).max()
        assert np.abs(J @ a_p + gamma).max() <= 1e-10 * scale and np.abs(J @ N).max() <= 1e-10 * np.abs(J).max()
        a_svd, N_svd = null_space.svd_null_space(J, gamma)
        assert N.shape == N_svd.shape
        M = pin.crba(m.model, m.model.createData(), s.q)
        M = np.triu(M) + np.triu(M, 1).T
        b = s.tau - pin.nonLinearEffects(m.model, m.model.createData(), s.q, s.v)
        exact = [a0 + B @ np.linalg.solve(B.T @ M @ B, B.T @ (b - M @ a0)) for a0, B in ((a_p, N), (a_svd, N_svd))]
        assert np.abs(exact[0] - exact[1]).max() <= 1e-9 * np.abs(exact[1]).max()
        a = core.forward_dynamics(cm, cm.create_data(), s.q, s.v, s.tau, "nullspace").a  # no springs: tau alone
        np.testing.assert_allclose(a, exact[0], rtol=0, atol=1e-9 * np.abs(exact[0]).max())


def test_the_partition_leaves_a_state_with_no_rigid_answer_to_the_svd(load_cached):
    m = load_cached("deployable_9rr12uru")
    cm, cd = m.closure_model, m.closure_model.create_data()
    q, v, _, _ = inconsistent_state(m)
    J, gamma, _ = forward._rows_and_drift(cm, cd, q, v, None)
    assert null_space.partitioned_null_space(cd, J, gamma) is None
    with pytest.raises(InconsistentMotion):
        null_space.svd_null_space(J, gamma)


def test_the_svd_allows_a_drifted_state_s_inconsistency_to_its_drift_and_no_further():
    """Three rows on four coordinates, the third the sum of the first two: gamma with a part 0.5 d |gamma|
    along the left null vector passes at drift d (refused at d = 0: on the manifold it is a velocity with
    no rigid answer), 20 d |gamma| is refused at d; the particular solution solves the consistent part."""
    rng = np.random.default_rng(3)
    J = rng.standard_normal((3, 4))
    J[2] = J[0] + J[1]
    u = np.array([1.0, 1.0, -1.0]) / np.sqrt(3.0)
    gamma0, d = J @ np.array([0.3, -0.2, 0.5, 0.1]), 1e-7
    gamma = gamma0 + 0.5 * d * np.linalg.norm(gamma0) * u
    a_p, N = null_space.svd_null_space(J, gamma, d)
    assert N.shape == (4, 2) and np.abs(J @ N).max() < 1e-14
    np.testing.assert_allclose(J @ a_p + gamma0, 0.0, atol=1e-14)
    with pytest.raises(InconsistentMotion):
        null_space.svd_null_space(J, gamma)
    with pytest.raises(InconsistentMotion):
        null_space.svd_null_space(J, gamma0 + 20 * d * np.linalg.norm(gamma0) * u, d)
