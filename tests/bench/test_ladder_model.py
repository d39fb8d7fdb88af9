"""The ladder of four-bar loops (`mechkit.bench.ladder_model`): its mobility, its assembly at q = 0, its
exact accelerations (`mechkit.bench.ladder.exact_accelerations`) against the core's KKT and lcaba."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.bench.ladder import exact_accelerations
from mechkit.bench.ladder_model import ladder


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
    assert np.max(np.abs(m.forward_dynamics(q, v, tau, "lcaba").a - exact)) <= 1e-10 * scale


def test_ladder_rejects_bad_sizes():
    with pytest.raises(InvalidParameters, match="n"):
        ladder(0)
