"""The plan of one sample of inverse dynamics (`mechkit.core.inverse_plan`): its world vectors are the kernels'
from the gathered placements, a data used with another model gets its own plan, and the one-sample call over it
gives the numbers of the unplanned steps (gather, kernel, SVD-backed solve, SVD null spaces) to 1e-13 on random
states of every registry mechanism."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit.bench.sampling import make_samples
from mechkit.catalog import registry
from mechkit.core import determinacy, efforts, inverse, inverse_plan
from mechkit.core.inverse_plan import plan

TOL = 1e-13


def _close(x: np.ndarray, y: np.ndarray, cond: float = 1.0) -> bool:
    """Equal to TOL relative, or to what rounding becomes through a solve of condition `cond` (two algorithms)."""
    tol = max(TOL, 10 * np.finfo(float).eps * cond)
    return float(np.max(np.abs(x - y), initial=0.0)) <= tol * max(1.0, float(np.max(np.abs(y), initial=0.0)))


@pytest.fixture(scope="module", params=registry.names())
def case(request, load_cached):
    m = load_cached(request.param)
    return m, make_samples(m, 3, seed=11)


def test_world_vectors_are_the_kernels_of_the_gathered_placements(case):
    m, samples = case
    cm, cd = m.closure_model, m.closure_model.create_data()
    p = plan(cm, cd)
    for s in samples:
        pin.computeJointJacobians(cm.model, cd.pin, s.q)
        p.fill_world()
        G = cd.used_placements()
        np.testing.assert_allclose(p.rows_world, cm.kernel.world(G), rtol=0, atol=1e-14)
        np.testing.assert_allclose(p.full_world, cm.full_kernel.world(G), rtol=0, atol=1e-14)
    assert plan(cm, cd) is p
    other = cm.with_actuation(cm.actuated[:1])
    assert plan(other, cd) is not p and plan(other, cd).statics.shape[1] == 1 + cm.kernel.size


def _reference(m, s):
    """The unplanned steps: gathered placements, the kernel, the generic solve, SVD null spaces."""
    cm, cd = m.closure_model, m.closure_model.create_data()
    pin.computeJointJacobians(cm.model, cd.pin, s.q)
    b = pin.rnea(cm.model, cd.pin, s.q, s.v, s.a).copy()
    passive = m.passive_forces(s.q, s.v)
    b = b if passive is None else b - passive
    P = cd.oMi.copy()
    G = inverse_plan.used_placements(cm, P[None])
    _, J, W = cm.kernel.evaluate(G, cd.J[None], s.q[None])
    x = efforts.solve(cm, determinacy.system(cm, J), b[None], True, "min_norm")[0][0]
    na, k = len(cm.actuated), cm.kernel
    reactions = k.joint_loads(W[0], x[na:], P[1:, :, 3], k.cut_points(G[0]))
    reactions[: P.shape[0] - 1] += inverse.tree_wrenches(P, cd.f)
    full = cm.full_kernel
    _, Jf, Wf = full.evaluate(G, cd.J[None], s.q[None])
    null = determinacy.svd_null_spaces(determinacy.system(cm, Jf))
    flags = determinacy.determinacy(cm, cd, G, cd.J[None], s.q[None], P[None, 1:, :, 3], k.cut_points(G), null, Wf)
    return x, reactions, flags[0][0], flags[1][0]


def test_one_sample_gives_the_unplanned_numbers(case):
    m, samples = case
    if m.idle:
        pytest.skip("idle freedoms go through the batch")
    for s in samples:
        one = m.inverse_dynamics(s.q, s.v, s.a)
        x, reactions, flags, effort_flags = _reference(m, s)
        cond = one.condition  # the redundant truss's min-norm split and the SVD differ by rounding times it
        assert _close(np.concatenate([one.effort_values, one.multipliers]), x, cond)
        assert _close(one.reaction_values, reactions, cond)
        np.testing.assert_array_equal(one.determinate, flags)
        np.testing.assert_array_equal(one.efforts_determinate_values, effort_flags)
