"""`mechkit.export.extended_urdf`: the tree URDF and its YAML sidecar, read as Gepetto's loader does,
reproduce mechkit's constrained dynamics."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit.export import to_extended_urdf

from .exported import NAMES, load_extended_urdf, other_pose


@pytest.mark.parametrize("name", NAMES)
def test_extended_urdf_round_trip_gives_the_same_dynamics(name, load_cached):
    """The tree URDF + YAML sidecar, read as Gepetto's loader does, reproduce mechkit's constrained dynamics."""
    m = load_cached(name)
    urdf, sidecar = to_extended_urdf(m)
    model, constraints, motors = load_extended_urdf(urdf, sidecar)
    assert motors == list(m.actuated)
    q = other_pose(m)
    v = m.velocities(q, np.ones(len(m.actuated)))
    tau = np.zeros(m.model.nv)
    tau[m.v_index(m.actuated[0])] = 0.3
    cms = pin.StdVec_RigidConstraintModel()
    for c in constraints:
        cms.append(c)
    cds = pin.StdVec_RigidConstraintData()
    for c in cms:
        cds.append(c.createData())
    data = model.createData()
    pin.initConstraintDynamics(model, data, cms, cds)
    a = pin.constraintDynamics(model, data, q, v, tau, cms, cds, pin.ProximalSettings(1e-12, 1e-9, 30))
    expected = m.forward_dynamics(q, v, tau, "kkt").a
    assert np.max(np.abs(a - expected)) <= 1e-8 * max(1.0, np.max(np.abs(expected)))
