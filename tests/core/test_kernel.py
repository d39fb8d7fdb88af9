"""The closure kernel (`mechkit.core.kernel`): its rows against Pinocchio's frame calls, its Jacobian as
row wrenches times the world joint Jacobians, its residuals and cut points from placements, and the
vectorised velocities / accelerations it serves against their single-sample path and the closure
identities."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit.base.spatial import cross, skew
from mechkit.bench.sampling import make_samples
from mechkit.catalog import registry

LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED


def _frame_rows(model: pin.Model, data: pin.Data, cuts: list) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Residual, Jacobian and drift from per-frame Pinocchio calls (the rows' definition, frame by frame);
    data after `computeJointJacobians` and `forwardKinematics(q, v, 0)`, frames updated."""
    e, J, g = [], [], []
    for cut in cuts:
        Ja = pin.getFrameJacobian(model, data, cut.frame_a, LWA).reshape(6, -1)
        Jb = pin.getFrameJacobian(model, data, cut.frame_b, LWA).reshape(6, -1)
        va, vb = (pin.getFrameVelocity(model, data, f, LWA) for f in (cut.frame_a, cut.frame_b))
        aa, ab = (pin.getFrameClassicalAcceleration(model, data, f, LWA) for f in (cut.frame_a, cut.frame_b))
        oMa, oMb = data.oMf[cut.frame_a], data.oMf[cut.frame_b]
        d, dv, wa, wb = oMb.translation - oMa.translation, vb.linear - va.linear, va.angular, vb.angular
        for t in (oMa.rotation @ cut.positions).T:
            e.append(t @ d)
            J.append(t @ (Jb[:3] - Ja[:3] + skew(d) @ Ja[3:]))
            g.append(t @ (ab.linear - aa.linear + cross(d, aa.angular) + cross(dv, wa) + cross(dv + cross(d, wa), wa)))
        for u_local, w_local in cut.alignments:
            u, w = oMa.rotation @ u_local, oMb.rotation @ w_local
            n = cross(w, u)
            e.append(u @ w)
            J.append(n @ (Jb[3:] - Ja[3:]))
            g.append(n @ (ab.angular - aa.angular) + (cross(cross(wb, w), u) + cross(w, cross(wa, u))) @ (wb - wa))
    return np.array(e), np.array(J).reshape(-1, model.nv), np.array(g)


@pytest.fixture(scope="module", params=registry.names())
def case(request, load_cached):
    m = load_cached(request.param)
    return m, make_samples(m, 4)


def test_rows_equal_the_frame_calls(case):
    """Off the closure manifold too (a perturbed q, any v): residual, Jacobian, drift to rounding."""
    m, _ = case
    rng = np.random.default_rng(3)
    for _ in range(3):
        q = pin.integrate(m.model, m.home_q, 0.2 * rng.standard_normal(m.model.nv))
        v = rng.standard_normal(m.model.nv)
        data = m.model.createData()
        pin.computeJointJacobians(m.model, data, q)
        pin.forwardKinematics(m.model, data, q, v, np.zeros(m.model.nv))
        pin.updateFramePlacements(m.model, data)
        e, J, g = _frame_rows(m.model, data, m.cuts)
        scale = max(1.0, np.abs(g).max())
        assert np.abs(m.closure_residual(q) - e).max() < 1e-13
        assert np.abs(m.closure_jacobian(q) - J).max() < 1e-13 * max(1.0, np.abs(J).max())
        assert np.abs(m.closure_drift(q, v) - g).max() < 1e-12 * scale


def test_batched_equals_single_and_the_closure_identities(case):
    """Velocities and accelerations of all samples at once equal the single-sample calls to 1e-13, and
    satisfy J v = 0, J a + gamma = 0 (in the least-squares sense where rows are redundant)."""
    m, samples = case
    names = list(samples[0].input_names)
    Q = np.array([s.q for s in samples])
    V = m.velocities_batch(Q, np.array([s.rates for s in samples]), names)
    A = m.accelerations_batch(Q, V, np.array([s.accelerations for s in samples]), names)
    for i, s in enumerate(samples):
        v = m.velocities(s.q, s.rates, names)
        a = m.accelerations(s.q, v, s.accelerations, names)
        for batched, single in ((V[i], v), (A[i], a)):
            assert np.abs(batched - single).max() <= 1e-13 * max(1.0, np.abs(single).max())
        J = m.closure_jacobian(s.q)
        assert np.abs(J @ v).max() < 1e-10 * max(1.0, np.abs(v).max())
        gamma, scale = m.closure_drift(s.q, v), max(1.0, np.abs(a).max())
        # every row, redundant ones too: the samples' velocities continue at second order
        assert np.abs(J @ a + gamma).max() < 1e-9 * max(scale, np.abs(gamma).max())


def test_drift_is_the_second_derivative(load_cached):
    """d2e/dt2 along q(t) = q exp(t v + t^2 a / 2), by central differences, equals J a + gamma."""
    m = load_cached("parallel_2t1r")
    rng = np.random.default_rng(5)
    q, v, a = m.home_q, rng.standard_normal(m.model.nv), rng.standard_normal(m.model.nv)
    h = 1e-4

    def e(t):
        return m.closure_residual(pin.integrate(m.model, q, t * v + 0.5 * t * t * a))

    fd = (e(h) - 2 * e(0.0) + e(-h)) / h**2
    assert np.abs(fd - (m.closure_jacobian(q) @ a + m.closure_drift(q, v))).max() < 1e-5


def test_motion_study_kinematics_equal_the_mechanism_calls(load_cached):
    """The study's batched v, a (after the per-sample solves from the polynomial warm start) equal
    `Mechanism.velocities` / `accelerations` at its q, and its tree axes the joints' world axes."""
    from mechkit import motion
    from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_DURATION, motion_law

    mech = load_cached("parallel_2t1r")
    law = motion.from_callable(mech, motion_law, np.linspace(0.2, MOTION_DURATION, 40))
    r = motion.study(mech, law)
    names = list(law.names)
    data = mech.model.createData()
    for i in range(len(r.t)):
        v = mech.velocities(r.q[i], law.rates[i], names)
        a = mech.accelerations(r.q[i], v, law.accelerations[i], names)
        assert np.abs(r.v[i] - v).max() <= 1e-12 * max(1.0, np.abs(v).max())
        assert np.abs(r.a[i] - a).max() <= 1e-11 * max(1.0, np.abs(a).max())
        pin.forwardKinematics(mech.model, data, r.q[i])
        for j in range(1, mech.model.njoints):
            S = np.asarray(data.joints[j].S).reshape(6)
            axis = data.oMi[j].rotation @ (S[3:] if np.linalg.norm(S[3:]) > 0 else S[:3])
            assert np.abs(r.axes[i, j - 1] - axis / np.linalg.norm(axis)).max() < 1e-14


@pytest.mark.parametrize("name", registry.names())
def test_row_wrenches_give_the_closure_jacobian_and_the_residuals(name, load_cached):
    """Off the closure (random q): W^T data.J on the support mask, the residuals and the cut points p_b
    from one gather equal the frame-by-frame Jacobian, residuals and frame origins (kept and full rows)."""
    m = load_cached(name)
    model = m.model
    rng = np.random.default_rng(3)
    for _ in range(3):
        q = pin.integrate(model, m.home_q, 0.3 * rng.standard_normal(model.nv))
        data = model.createData()
        pin.computeJointJacobians(model, data, q)
        pin.forwardKinematics(model, data, q, np.zeros(model.nv), np.zeros(model.nv))
        pin.updateFramePlacements(model, data)
        for kernel in (m.closure_model.kernel, m.closure_model.full_kernel):
            G = np.array([data.oMi[int(j)].homogeneous for j in kernel.joints])[None]
            e, J, W = kernel.evaluate(G, data.J[None], q[None])
            e_ref, J_ref, _ = _frame_rows(model, data, kernel.cuts)
            assert np.max(np.abs(e[0] - e_ref), initial=0.0) < 1e-13
            assert np.max(np.abs(J[0] - J_ref), initial=0.0) < 1e-13 * max(1.0, np.max(np.abs(J_ref), initial=0.0))
            assert np.max(np.abs(kernel.jacobian(W, data.J[None], q[None]) - J), initial=0.0) == 0.0
            for c, cut in enumerate(kernel.cuts):
                np.testing.assert_allclose(kernel.cut_points(G)[0, c], data.oMf[cut.frame_b].translation, atol=1e-14)


@pytest.mark.parametrize("name", ["four_bar", "parallel_2t1r", "rocket_gimbal"])
def test_load_map_is_joint_loads_as_a_matrix(name, load_cached):
    """`load_map` times any multipliers equals `joint_loads` of them, one sample and batched."""
    m = load_cached(name)
    cm, cd = m.closure_model, m.closure_model.create_data()
    rng = np.random.default_rng(1)
    for kernel in (cm.kernel, cm.full_kernel):
        for s in make_samples(m, 2):
            pin.computeJointJacobians(cm.model, cd.pin, s.q)
            G = cd.used_placements()
            W, origins, points = kernel.row_wrenches(G), cd.oMi[1:, :, 3], kernel.cut_points(G)
            lam = rng.standard_normal((4, kernel.size))
            want = kernel.joint_loads(W, lam, origins, points)
            got = np.einsum("jcr,nr->njc", kernel.load_map(W, origins, points), lam[:, : kernel.cut_size])
            np.testing.assert_allclose(got, want, atol=1e-13 * np.abs(want).max())
            batched = kernel.load_map(W[None], origins[None], points[None])[0]
            np.testing.assert_array_equal(batched, kernel.load_map(W, origins, points))
