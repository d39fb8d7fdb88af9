"""The force method: equilibrium kept, compatibility reached (the energy is stationary along every
self-stress)."""

from __future__ import annotations

import numpy as np

import mechkit
from mechkit.elastic import ElasticModel, statics


def test_compatible_solution_is_an_equilibrium_of_least_energy():
    m = mechkit.load("four_bar", rows="spatial")
    e = ElasticModel(m)
    pose = statics.evaluate(e.idealisation, m.home_q[None])
    body = e.body("coupler_link")
    b, R0 = statics.unit_loads(m.model, pose, np.array([body]), pose.t[:, [body]])
    x = statics.particular(pose, b)
    assert np.abs(pose.A @ x - b).max() < 1e-12 * np.abs(b).max()
    c = e.idealisation.drive_compliance
    out = statics.compatible(pose, c, R0 + pose.reaction_map @ x[:, None], x[:, : pose.efforts])
    # along every self-stress the energy gradient vanishes
    YR = pose.reaction_map @ pose.null[:, None]
    gradient = np.einsum("njas,njab,njbk->nsk", YR, pose.compliance, out.reactions)
    energy_scale = np.einsum("njak,njab,njbk->k", out.reactions, pose.compliance, out.reactions)
    assert pose.null.shape[2] == 3 and np.abs(gradient).max() < 1e-9 * np.sqrt(energy_scale.max())
    assert out.determinate.all() and not out.rigid_determinate.all()


def test_a_pose_that_does_not_close_is_refused():
    import pytest

    from mechkit.base.exceptions import InvalidParameters

    m = mechkit.load("four_bar")
    e = ElasticModel(m)
    with pytest.raises(InvalidParameters, match="does not close"):
        e.stiffness(m.home_q + 0.01, "coupler_link")
