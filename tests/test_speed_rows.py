"""The fast paths compute the same physics: closure rows as world wrenches, the ladder, lcaba."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.base.spatial import cross_batch
from mechkit.bench.ladder import exact_accelerations
from mechkit.bench.ladder_model import LCABA_DEFAULTS, LoopConstrainedABA, ladder
from mechkit.catalog import registry
from mechkit.core.row_wrenches import RowWrenches


@pytest.mark.parametrize("name", registry.names())
def test_wrench_rows_give_the_closure_jacobian(name, load_cached):
    """W^T data.J on the support mask equals the closure rows' own Jacobian (frame Jacobians)."""
    m = load_cached(name)
    q = m.home_q
    J = m.closure_jacobian(q)  # also leaves data.J and oMi at q
    for rows in (m.rows, m.full_rows):
        rw = RowWrenches(rows)
        got = rw.jacobian(rw.wrenches(np.array([M.homogeneous for M in m.data.oMi])[None]), m.data.J[None])[0]
        want = J if rows is m.rows else rows.jacobian(m.data)
        assert np.max(np.abs(got - want), initial=0.0) < 1e-13 * max(1.0, np.max(np.abs(want), initial=0.0))


def test_cross_batch_is_the_cross_product():
    rng = np.random.default_rng(3)
    a, b = rng.normal(size=(4, 5, 3)), rng.normal(size=(4, 5, 3))
    assert np.max(np.abs(cross_batch(a, b) - np.cross(a, b))) < 1e-15


@pytest.mark.parametrize("loops", [1, 3, 8])
def test_ladder_mobility_and_lcaba_accelerations(loops):
    m = ladder(loops)
    assert m.mobility().dof == loops and m.mobility().redundant == 0
    assert np.max(np.abs(m.closure_residual(m.home_q))) < 1e-14  # assembled at q = 0
    rng = np.random.default_rng(loops)
    q = m.home_q
    v = m.velocities(q, rng.normal(size=loops))
    tau = rng.normal(0.0, 0.1, m.model.nv)
    exact = exact_accelerations(m, q, v, tau)
    scale = np.max(np.abs(exact))
    # the refined KKT satisfies the closure and agrees with the core's dense KKT
    assert np.max(np.abs(m.closure_jacobian(q) @ exact + m.closure_drift(q, v))) < 1e-10 * scale
    assert np.max(np.abs(m.forward_dynamics(q, v, tau, "kkt").a - exact)) < 1e-10 * scale
    a = LoopConstrainedABA(m, *LCABA_DEFAULTS)(q, v, tau)
    assert np.max(np.abs(a - exact)) <= 1e-10 * scale


def test_ladder_rejects_bad_sizes():
    with pytest.raises(InvalidParameters, match="n"):
        ladder(0)
