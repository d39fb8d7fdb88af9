"""The fast forward-dynamics paths compute the same physics: the wrapper's check on Pinocchio's own rows,
its plain-array fast path and shared batch validation, and the certified loop-constrained ABA."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit.base.exceptions import ClosureNotConverged, InvalidArgument
from mechkit.bench.ladder import exact_accelerations
from mechkit.bench.ladder_model import LCABA_DEFAULTS, LoopConstrainedABA, ladder
from mechkit.bench.sampling import make_samples
from mechkit.core import forward

PROXIMAL = ["four_bar", "five_bar", "parallel_2t1r", "ten_bar", "deployable_9rr12uru"]


@pytest.mark.parametrize("name", PROXIMAL)
def test_pinocchio_rows_left_by_constraint_dynamics_are_fresh_and_solved(name, load_cached):
    """getConstraintsJacobian / primal_rhs_contact after constraintDynamics are those of (q, v), not stale,
    and the wrapper's accelerations satisfy them as tightly as mechkit's own rows."""
    m = load_cached(name)
    samples = make_samples(m, 3)
    solver = m._forward
    cms, cds = solver.constraints()
    for s in samples:  # alternate states: a stale Jacobian would be the previous sample's
        a = m.forward_dynamics(s.q, s.v, s.tau).a
        J = pin.getConstraintsJacobian(m.model, solver.pin_data, cms, cds)
        gamma = -solver.pin_data.primal_rhs_contact[:J.shape[0]]
        fresh = m.model.createData()
        pin.computeJointJacobians(m.model, fresh, s.q)
        fresh_cds = pin.StdVec_RigidConstraintData()
        for cm in cms:
            fresh_cds.append(cm.createData())
            cm.calc(m.model, fresh, fresh_cds[len(fresh_cds) - 1])
        assert np.max(np.abs(J - pin.getConstraintsJacobian(m.model, fresh, cms, fresh_cds))) <= 1e-13 * np.max(np.abs(J))
        Jm, gm = m.closure_jacobian(s.q), m.closure_drift(s.q, s.v)
        ours = np.max(np.abs(Jm @ a + gm)) / np.max(np.linalg.norm(Jm, axis=1))
        pins = np.max(np.abs(J @ a + gamma)) / np.max(np.linalg.norm(J, axis=1))
        # the two row sets measure the same closure: residuals of one order (both tiny where consistent)
        assert pins <= 10 * ours + 1e-10 * np.max(np.abs(a)) and ours <= 10 * pins + 1e-10 * np.max(np.abs(a))


@pytest.mark.parametrize("name", ["four_bar", "parallel_2t1r", "ten_bar"])
def test_proximal_agrees_with_kkt_on_the_manifold(name, load_cached):
    m = load_cached(name)
    for s in make_samples(m, 3):
        kkt = m.forward_dynamics(s.q, s.v, s.tau, "kkt").a
        prox = m.forward_dynamics(s.q, s.v, s.tau).a
        assert np.max(np.abs(prox - kkt)) <= 1e-8 * np.max(np.abs(kkt))


def test_off_manifold_result_is_checked_on_the_rows_solved(load_cached):
    """Off the manifold (Baumgarte on a perturbed state) the check runs on Pinocchio's rows, which
    include the stabilisation: an unconverged result is refused there too."""
    m = load_cached("five_bar")
    q = m.home_q + 1e-3
    v = m.velocities(m.home_q, [1.0, -0.5])
    res = m.forward_dynamics(q, v, np.zeros(m.model.nv), baumgarte=(100.0, 20.0))
    J = pin.getConstraintsJacobian(m.model, m._forward.pin_data, *m._forward.constraints())
    gamma = -m._forward.pin_data.primal_rhs_contact[:J.shape[0]]
    assert np.max(np.abs(J @ res.a + gamma)) <= 1e-8 * (np.max(np.abs(J)) * np.max(np.abs(res.a)) + np.max(np.abs(gamma)))
    with pytest.raises(ClosureNotConverged, match="J a \\+ gamma"):
        m.forward_dynamics(q, v, np.zeros(m.model.nv), mu=1e3, max_iter=1, baumgarte=(100.0, 20.0))


@pytest.mark.parametrize("method", ["proximal", "kkt"])
def test_fast_path_and_batch_give_the_per_sample_numbers(method, load_cached):
    m = load_cached("parallel_2t1r")
    samples = make_samples(m, 3)
    Q, V, T = (np.array([getattr(s, k) for s in samples]) for k in ("q", "v", "tau"))
    batch = m.forward_dynamics(Q, V, T, method)
    for i, s in enumerate(samples):
        plain = m.forward_dynamics(np.asarray(s.q, float), np.asarray(s.v, float), np.asarray(s.tau, float), method)
        listed = m.forward_dynamics(s.q.tolist(), s.v.tolist(), s.tau.tolist(), method)  # through arguments.state
        assert np.max(np.abs(batch.a[i] - plain.a)) <= 1e-13 * np.max(np.abs(plain.a))
        assert np.max(np.abs(batch.constraint_force[i] - plain.constraint_force)) <= 1e-13 * max(np.max(np.abs(plain.constraint_force)), 1.0)
        assert np.max(np.abs(listed.a - plain.a)) <= 1e-13 * np.max(np.abs(plain.a))
    assert batch.a.shape == (3, m.model.nv) and batch.constraint_force.shape == (3, m.model.nv)


def test_fast_path_still_refuses_bad_arrays(load_cached):
    m = load_cached("four_bar")
    q, v, tau = m.home_q.copy(), np.zeros(m.model.nv), np.zeros(m.model.nv)
    assert forward.plain_state(q, v, tau, m.model.nq, m.model.nv)
    for bad in (np.nan, np.inf):
        tau[0] = bad
        assert not forward.plain_state(q, v, tau, m.model.nq, m.model.nv)
        with pytest.raises(InvalidArgument, match="tau"):
            m.forward_dynamics(q, v, tau)
    assert forward.plain_state(q, v, np.full(m.model.nv, 1e300), m.model.nq, m.model.nv)  # finite, however large
    with pytest.raises(InvalidArgument, match="q"):
        m.forward_dynamics(q.astype(np.float32)[:-1], v, np.zeros(m.model.nv))


@pytest.mark.parametrize("loops", [1, 4, 16, 32])
def test_lcaba_on_the_ladder_against_the_exact_accelerations(loops):
    m = ladder(loops)
    lc = LoopConstrainedABA(m, *LCABA_DEFAULTS)
    for seed in (0, 1):
        rng = np.random.default_rng(seed)
        q = m.home_q
        v = m.velocities(q, rng.normal(size=loops))
        tau = rng.normal(0.0, 0.1, m.model.nv)
        exact = exact_accelerations(m, q, v, tau)
        a = lc(q, v, tau)
        assert np.max(np.abs(a - exact)) <= 1e-10 * np.max(np.abs(exact))
        J, gamma = m.closure_jacobian(q), m.closure_drift(q, v)
        assert np.max(np.abs(J @ a + gamma)) <= 1e-9 * np.max(np.abs(J)) * np.max(np.abs(exact))


@pytest.mark.parametrize("name", ["four_bar", "five_bar", "parallel_2t1r", "ten_bar"])
def test_lcaba_on_registered_mechanisms_against_the_kkt(name, load_cached):
    m = load_cached(name)
    lc = LoopConstrainedABA(m)
    for s in make_samples(m, 3):
        kkt = m.forward_dynamics(s.q, s.v, s.tau, "kkt").a
        assert np.max(np.abs(lc(s.q, s.v, s.tau) - kkt)) <= 1e-9 * np.max(np.abs(kkt))


def test_lcaba_refuses_what_it_does_not_converge_on(load_cached):
    m = load_cached("tetra_3rr3uru")
    s = make_samples(m, 1)[0]
    with pytest.raises(ClosureNotConverged, match="lcaba"):
        LoopConstrainedABA(m)(s.q, s.v, s.tau)
    lc = LoopConstrainedABA(ladder(8), max_iter=3)
    with pytest.raises(ClosureNotConverged, match="lcaba"):
        lc(np.zeros(lc.nq), np.zeros(lc.model.nv), np.ones(lc.model.nv))
    with pytest.raises(InvalidArgument, match="mu"):
        LoopConstrainedABA(ladder(1), mu=0.0)
    with pytest.raises(InvalidArgument, match="v"):
        LoopConstrainedABA(ladder(1))(np.zeros(3), np.zeros((2, 3)), np.zeros(3))


@pytest.mark.parametrize(("loops", "max_iter"), [(1, 6), (4, 8), (16, 20)])
def test_lcaba_measures_the_closure_error_of_its_final_accelerations(loops, max_iter):
    """Stopped at max_iter, lcaba's own residual is the one before its last step; the refusal reports
    that plus J g, which is the error of the final accelerations on Pinocchio's rows (as constraintDynamics
    poses them at the same state)."""
    m = ladder(loops)
    lc = LoopConstrainedABA(m, max_iter=max_iter)
    q, v, tau = m.home_q, m.velocities(m.home_q, np.ones(loops)), np.full(m.model.nv, 0.05)
    with pytest.raises(ClosureNotConverged) as err:
        lc(q, v, tau)
    a = lc.data.ddq.copy()
    solver = m._forward
    solver.solve(q, v, tau, "proximal", mu=1e-11, accuracy=1e-12, max_iter=20, baumgarte=None)
    J = pin.getConstraintsJacobian(m.model, solver.pin_data, *solver.constraints())
    true = np.max(np.abs(J @ a - solver.pin_data.primal_rhs_contact[:J.shape[0]]))
    assert abs(err.value.residual - true) <= 1e-9 * true + 1e-14 * np.max(np.abs(J)) * np.max(np.abs(a))  # rounding of J a
    assert err.value.residual != lc.prox.absolute_residual  # not the stale value
