"""Coupling rows (`mechkit.core.coupling_rows`): a coupling resolves on one-freedom joints only, and its
row's Jacobian and drift are the derivatives of its residual."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit import core
from mechkit.base.exceptions import MalformedDescription
from mechkit.core.coupling_rows import coupling_drift, coupling_jacobian, coupling_residual, coupling_row


def _two_joints():
    model = pin.Model()
    a = model.addJoint(0, pin.JointModelRZ(), pin.SE3.Identity(), "a")
    model.addJoint(a, pin.JointModelRUBZ(), pin.SE3.Identity(), "b")
    model.addJoint(0, pin.JointModelSpherical(), pin.SE3.Identity(), "ball")
    return model


def test_a_coupling_resolves_on_one_freedom_joints_only():
    model = _two_joints()
    row = coupling_row(model, core.Coupling("gear", (("a", 1.0),), (("b", -2.0),), (0.1, 1.0)))
    np.testing.assert_array_equal(row.unbounded, [False, True])  # b is continuous: its value is an angle
    np.testing.assert_array_equal(row.follower, [1.0, 0.0])
    np.testing.assert_array_equal(row.leader, [0.0, -2.0])
    for bad, words in (
        (core.Coupling("x", (("nope", 1.0),)), "not in the model"),
        (core.Coupling("x", (("ball", 1.0),)), "3 freedoms"),
        (core.Coupling("x", ()), "no follower"),
        (core.Coupling("x", (("a", 1.0),), polynomial=(np.nan,)), "finite"),
    ):
        with pytest.raises(MalformedDescription, match=words):
            coupling_row(model, bad)


def test_jacobian_and_drift_are_the_derivatives_of_the_residual():
    """A cubic coupling of a bounded and a continuous joint, at random states: J dq is the central
    difference of e along q (+) t dq, and gamma the central difference of J v along q (+) t v."""
    model = _two_joints()
    rows = [coupling_row(model, core.Coupling("cam", (("a", 1.0),), (("b", -2.0),), (0.1, 1.0, 0.5, -0.3), 0.2, 0.4))]
    rng = np.random.default_rng(7)
    h, seen = 1e-6, 0.0
    for _ in range(3):
        q = pin.integrate(model, pin.neutral(model), rng.standard_normal(model.nv))
        dq, v = rng.standard_normal(model.nv), rng.standard_normal(model.nv)
        J = coupling_jacobian(rows, q, model.nv)[0]
        fd = (
            coupling_residual(rows, pin.integrate(model, q, h * dq))
            - coupling_residual(rows, pin.integrate(model, q, -h * dq))
        ) / (2 * h)
        assert np.abs(J @ dq - fd).max() < 1e-7 * max(1.0, np.abs(fd).max())
        jv = [coupling_jacobian(rows, pin.integrate(model, q, t * v), model.nv)[0] @ v for t in (h, -h)]
        fd = (jv[0] - jv[1]) / (2 * h)
        gamma = coupling_drift(rows, q, v)
        assert np.abs(gamma - fd).max() < 1e-6 * max(1.0, np.abs(fd).max())
        seen = max(seen, np.abs(gamma).max())
    assert seen > 1e-3  # the cubic's curvature is seen
