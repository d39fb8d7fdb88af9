"""Forward dynamics (`mechkit.core.forward`): every method against the exact null-space solve, the
check on the rows each method solved, the refusal of states with no rigid answer, lcaba."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit import core
from mechkit.base.arguments import plain_state
from mechkit.base.exceptions import ConstraintViolated, InconsistentMotion, InvalidArgument, SingularConfiguration
from mechkit.bench.ladder import exact_accelerations
from mechkit.bench.ladder_model import ladder
from mechkit.bench.sampling import make_samples
from mechkit.core import forward

from .no_rigid_answer import inconsistent_state

PROXIMAL = ["four_bar", "five_bar", "parallel_2t1r", "ten_bar", "deployable_9rr12uru"]
#: Where lcaba does not converge (measured; it refuses by name).
LCABA_DIVERGES = ("tetra_3rr3uru", "deployable_9rr12uru", "spherical_2dof", "rocket_gimbal")
EVERY = [
    "four_bar",
    "five_bar",
    "parallel_2t1r",
    "ten_bar",
    "tetra_3rr3uru",
    "deployable_9rr12uru",
    "spherical_2dof",
    "rocket_gimbal",
]


@pytest.mark.parametrize("name", PROXIMAL)
def test_pinocchio_rows_left_by_constraint_dynamics_are_fresh_and_solved(name, load_cached):
    """The anchors' Jacobian and drift after constraintDynamics are those of (q, v), not stale, and the
    wrapper's accelerations satisfy them as tightly as mechkit's own rows."""
    m = load_cached(name)
    legacy = None
    for s in make_samples(m, 3):  # alternate states: a stale Jacobian would be the previous sample's
        a = m.forward_dynamics(s.q, s.v, s.tau).a
        legacy = m.closure_data.legacy["proximal"]
        J = legacy.jacobian()
        gamma = legacy.drift(J.shape[0])
        fresh = core.LegacyConstraints(m.model, list(m.cuts))
        fresh.dynamics(s.q, s.v, s.tau, core.proximal_settings(1e-12, 1e-9, 20))
        assert np.max(np.abs(J - fresh.jacobian())) <= 1e-13 * np.max(np.abs(J))
        Jm, gm = m.closure_jacobian(s.q), m.closure_drift(s.q, s.v)
        ours = np.max(np.abs(Jm @ a + gm)) / np.max(np.linalg.norm(Jm, axis=1))
        pins = np.max(np.abs(J @ a + gamma)) / np.max(np.linalg.norm(J, axis=1))
        # the two row sets measure the same closure: residuals of one order (both tiny where consistent)
        assert pins <= 10 * ours + 1e-10 * np.max(np.abs(a)) and ours <= 10 * pins + 1e-10 * np.max(np.abs(a))


@pytest.mark.parametrize("name", EVERY)
def test_every_method_agrees_with_the_exact_null_space_solve(name, load_cached):
    """At states along finite motions (the bench's samples) every method gives the null-space solve's
    accelerations to 1e-6 relative (measured: 3e-9 at worst, the deployable's proximal), and all rows
    close to rounding."""
    m = load_cached(name)
    for s in make_samples(m, 3):
        exact = m.forward_dynamics(s.q, s.v, s.tau, "nullspace").a
        scale = np.max(np.abs(exact))
        J, gamma = m.closure_jacobian(s.q), m.closure_drift(s.q, s.v)
        for method in core.FORWARD_METHODS:
            try:
                a = m.forward_dynamics(s.q, s.v, s.tau, method).a
            except ConstraintViolated:
                assert method == "lcaba" and name in LCABA_DIVERGES
                continue  # lcaba does not converge on these; it says so
            assert np.max(np.abs(a - exact)) <= 1e-6 * scale, method
            assert np.max(np.abs(J @ a + gamma)) <= 1e-8 * (np.max(np.abs(J)) * scale + np.max(np.abs(gamma))), method


def test_no_rigid_answer_is_refused_by_every_method(load_cached):
    """On the deployable, a velocity in the null space of J but off the second-order cone: gamma has a
    part outside the range of J; accelerations and every forward-dynamics method refuse by name, and
    the least-squares accelerations are returned only when asked for."""
    m = load_cached("deployable_9rr12uru")
    q, v, tau, relative = inconsistent_state(m)
    assert relative > 1e-6, "every null direction continues at second order"
    delta = m.second_order_inconsistency(q, v)
    for method in core.FORWARD_METHODS:
        with pytest.raises((InconsistentMotion, ConstraintViolated)) as err:
            m.forward_dynamics(q, v, tau, method)
        if method != "lcaba":  # lcaba fails to converge first on the deployable
            assert isinstance(err.value, InconsistentMotion), method
    inputs = list(m.actuated)
    given = np.concatenate([np.atleast_1d(v[m.v_index(j)]) for j in inputs])
    with pytest.raises(InconsistentMotion):
        m.accelerations(q, v, np.zeros(len(given)))
    a = m.accelerations(q, v, np.zeros(len(given)), least_squares=True)
    residual = np.max(np.abs(m.closure_jacobian(q) @ a + m.closure_drift(q, v)))
    assert residual == pytest.approx(delta, rel=0.5)  # the least-squares compromise: of the size of delta


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
    legacy = m.closure_data.legacy["proximal"]
    J = legacy.jacobian()
    gamma = legacy.drift(J.shape[0])
    assert np.max(np.abs(J @ res.a + gamma)) <= 1e-8 * (
        np.max(np.abs(J)) * np.max(np.abs(res.a)) + np.max(np.abs(gamma))
    )
    with pytest.raises(ConstraintViolated, match="J a \\+ gamma"):
        m.forward_dynamics(q, v, np.zeros(m.model.nv), mu=1e3, max_iter=1, baumgarte=(100.0, 20.0))


@pytest.mark.parametrize("method", ["proximal", "kkt", "nullspace"])
def test_batch_and_lists_give_the_per_sample_numbers(method, load_cached):
    m = load_cached("parallel_2t1r")
    samples = make_samples(m, 3)
    Q, V, T = (np.array([getattr(s, k) for s in samples]) for k in ("q", "v", "tau"))
    batch = m.forward_dynamics_batch(Q, V, T, method)
    for i, s in enumerate(samples):
        plain = m.forward_dynamics(np.asarray(s.q, float), np.asarray(s.v, float), np.asarray(s.tau, float), method)
        listed = m.forward_dynamics(s.q.tolist(), s.v.tolist(), s.tau.tolist(), method)  # through arguments.sample
        assert np.max(np.abs(batch.a[i] - plain.a)) <= 1e-13 * np.max(np.abs(plain.a))
        assert np.max(np.abs(batch.constraint_force[i] - plain.constraint_force)) <= 1e-13 * max(
            np.max(np.abs(plain.constraint_force)), 1.0
        )
        assert np.max(np.abs(listed.a - plain.a)) <= 1e-13 * np.max(np.abs(plain.a))
    assert batch.a.shape == (3, m.model.nv) and batch.constraint_force.shape == (3, m.model.nv)


def test_fast_path_still_refuses_bad_arrays(load_cached):
    m = load_cached("four_bar")
    q, v, tau = m.home_q.copy(), np.zeros(m.model.nv), np.zeros(m.model.nv)
    assert plain_state(q, v, tau, m.model.nq, m.model.nv)
    for bad in (np.nan, np.inf):
        tau[0] = bad
        assert not plain_state(q, v, tau, m.model.nq, m.model.nv)
        with pytest.raises(InvalidArgument, match="tau"):
            m.forward_dynamics(q, v, tau)
    assert plain_state(q, v, np.full(m.model.nv, 1e300), m.model.nq, m.model.nv)  # finite, however large
    with pytest.raises(InvalidArgument, match="q"):
        m.forward_dynamics(q.astype(np.float32)[:-1], v, np.zeros(m.model.nv))


@pytest.mark.parametrize("loops", [1, 4, 16, 32])
def test_lcaba_on_the_ladder_against_the_exact_accelerations(loops):
    m = ladder(loops)
    for seed in (0, 1):
        rng = np.random.default_rng(seed)
        q = m.home_q
        v = m.velocities(q, rng.normal(size=loops))
        tau = rng.normal(0.0, 0.1, m.model.nv)
        exact = exact_accelerations(m, q, v, tau)
        a = m.forward_dynamics(q, v, tau, "lcaba").a
        assert np.max(np.abs(a - exact)) <= 1e-10 * np.max(np.abs(exact))
        J, gamma = m.closure_jacobian(q), m.closure_drift(q, v)
        assert np.max(np.abs(J @ a + gamma)) <= 1e-9 * np.max(np.abs(J)) * np.max(np.abs(exact))


def test_lcaba_certifies_the_long_ladder_at_its_first_margin():
    """On 64 loops lcaba's final closure error passes at the first step margin, in about 30 iterations as
    on one loop (the tighter margin alone takes 126 there: four times the time)."""
    m = ladder(64)
    rng = np.random.default_rng(0)
    q = m.home_q
    v, tau = m.velocities(q, rng.normal(size=64)), rng.normal(0.0, 0.1, m.model.nv)
    result = m.forward_dynamics(q, v, tau, "lcaba")
    exact = exact_accelerations(m, q, v, tau)
    assert result.iterations <= 40
    assert np.max(np.abs(result.a - exact)) <= 1e-9 * np.max(np.abs(exact))


@pytest.mark.parametrize("name", ["four_bar", "five_bar", "parallel_2t1r", "ten_bar"])
def test_lcaba_on_registered_mechanisms_against_the_kkt(name, load_cached):
    m = load_cached(name)
    for s in make_samples(m, 3):
        kkt = m.forward_dynamics(s.q, s.v, s.tau, "kkt").a
        assert np.max(np.abs(m.forward_dynamics(s.q, s.v, s.tau, "lcaba").a - kkt)) <= 1e-9 * np.max(np.abs(kkt))


def test_lcaba_refuses_what_it_does_not_converge_on(load_cached):
    m = load_cached("tetra_3rr3uru")
    s = make_samples(m, 1)[0]
    with pytest.raises(ConstraintViolated, match="lcaba"):
        m.forward_dynamics(s.q, s.v, s.tau, "lcaba")
    lad = ladder(8)
    with pytest.raises(ConstraintViolated, match="lcaba"):
        lad.forward_dynamics(np.zeros(lad.model.nq), np.zeros(lad.model.nv), np.ones(lad.model.nv), "lcaba", max_iter=3)


@pytest.mark.parametrize(("loops", "max_iter"), [(1, 6), (4, 8), (16, 20)])
def test_lcaba_measures_the_closure_error_of_its_final_accelerations(loops, max_iter):
    """Stopped at max_iter, lcaba's own residual is the one before its last step; the refusal reports
    that plus J g, the error of the final accelerations on Pinocchio's rows (as constraintDynamics
    poses them at the same state)."""
    m = ladder(loops)
    q, v, tau = m.home_q, m.velocities(m.home_q, np.ones(loops)), np.full(m.model.nv, 0.05)
    with pytest.raises(ConstraintViolated) as err:
        m.forward_dynamics(q, v, tau, "lcaba", max_iter=max_iter)
    a = m.closure_data.legacy["lcaba"].data.ddq.copy()
    check = core.LegacyConstraints(m.model, list(m.cuts))
    check.dynamics(q, v, tau, core.proximal_settings(1e-12, 1e-9, 20))
    J = check.jacobian()
    true = np.max(np.abs(J @ a + check.drift(J.shape[0])))
    assert abs(err.value.residual - true) <= 1e-9 * true + 1e-14 * np.max(np.abs(J)) * np.max(np.abs(a))


def _redundant_rows(lift):
    """Three rows on four coordinates, the third the sum of the first two plus `lift` (a redundant row
    lifted off by a state's drift), the exact solution of the first two, and the third's left null vector."""
    rng = np.random.default_rng(3)
    J = rng.standard_normal((3, 4))
    J[2] = J[0] + J[1] + lift * rng.standard_normal(4)
    u = np.array([1.0, 1.0, -1.0]) / np.sqrt(3.0)
    return J, u


@pytest.mark.parametrize("solved", [None, np.array([0, 1])])
def test_a_drifted_state_s_inconsistency_is_allowed_to_its_drift_and_no_further(solved):
    """gamma's part outside the range of J that no acceleration cancels is allowed to RANGE_TOL times the
    terms on the manifold (rounding) plus the state's relative drift d times |gamma| off it: a part of
    0.5 d |gamma| passes with d given (fails with d = 0, the old absolute limit), 20 d |gamma| is refused
    with it; the accelerations are judged on the rows solved (least squares, or the independent rows)."""
    d = 1e-6
    J, u = _redundant_rows(1e-12)
    gamma0 = J @ np.array([0.3, -0.2, 0.5, 0.1])  # consistent: a = -(0.3, -0.2, 0.5, 0.1)
    for part, passes in ((0.5, True), (20.0, False)):
        gamma = gamma0 + part * d * np.linalg.norm(gamma0) * u
        a = (
            np.linalg.lstsq(J[:2], -gamma[:2], rcond=None)[0]
            if solved is not None
            else np.linalg.pinv(J, rcond=1e-9) @ -gamma
        )
        if passes:
            forward.check_acceleration(J, a, gamma, "test", drift=d, solved=solved)
            with pytest.raises(InconsistentMotion):
                forward.check_acceleration(J, a, gamma, "test", solved=solved)
        else:
            with pytest.raises(InconsistentMotion):
                forward.check_acceleration(J, a, gamma, "test", drift=d, solved=solved)
    a = np.linalg.pinv(J, rcond=1e-9) @ -gamma0 + 1e-6  # a wrong acceleration: refused whatever the drift
    with pytest.raises(ConstraintViolated):
        forward.check_acceleration(J, a, gamma0, "test", drift=d, solved=solved)


def test_the_drift_lifts_a_redundant_row_s_singular_value_only_to_its_size():
    """A redundant row lifted by 1e-10 (above RANK_TOL, below the drift 1e-7) is still judged redundant
    with the drift given: its gamma part d/2 |gamma| passes; without the drift it is a row of its own and
    its solve is the rows' (here the least squares of two rows misses it: refused)."""
    d = 1e-7
    J, u = _redundant_rows(1e-10)
    gamma0 = J[:2] @ np.array([0.3, -0.2, 0.5, 0.1])
    gamma = np.concatenate([gamma0, [gamma0.sum()]]) + 0.5 * d * np.linalg.norm(gamma0) * u
    a = np.linalg.lstsq(J[:2], -gamma[:2], rcond=None)[0]
    forward.check_acceleration(J, a, gamma, "test", drift=d, solved=np.array([0, 1]))
    with pytest.raises((ConstraintViolated, InconsistentMotion)):
        forward.check_acceleration(J, a, gamma, "test", solved=np.array([0, 1]))


def test_the_fast_check_fails_safe_on_values_that_are_not_finite():
    """The check's norms in Python floats pass a closed result and fail where the accelerations or the
    drift are NaN or inf (even inf against inf), sending them to the full check, which refuses them."""
    rng = np.random.default_rng(1)
    J, a = rng.standard_normal((3, 5)), rng.standard_normal(5)
    gamma = -J @ a
    assert forward._closes(J, a, -gamma)
    assert not forward._closes(J, a + 1e-6, -gamma)  # a wrong acceleration
    for bad in (np.nan, np.inf):
        b = a.copy()
        b[0] = bad
        assert not forward._closes(J, b, -gamma)
        with pytest.raises(SingularConfiguration, match="non-finite"):
            forward.check_acceleration(J, b, gamma, "test")
        g = gamma.copy()
        g[0] = bad
        assert not forward._closes(J, b, -g) and not forward._closes(J, a, -g)
    assert forward._closes(np.zeros((0, 5)), a, np.zeros(0))  # no rows: nothing to violate
    at_rest = np.zeros(3)  # gamma = 0 (no velocity): judged against |J| |a|
    null = np.linalg.svd(J)[2][3:]  # accelerations J leaves free pass; any other, however small, does not
    assert forward._closes(J, null.T @ rng.standard_normal(2), at_rest)
    assert not forward._closes(J, 1e-9 * rng.standard_normal(5), at_rest)
