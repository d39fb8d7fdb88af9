"""`mechkit.mechanism_dynamics.MechanismDynamics`: forward dynamics at any model scale (the proximal
solver against the exact KKT one), unconverged results refused, forward then inverse dynamics returning
the efforts given with the springs in both (a part built from a closure model alone, as the facade's), and
Newton's law of every registered mechanism from its support reactions."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg
from conftest import support_balance_error

import mechkit
from mechkit import core
from mechkit.base.exceptions import ConstraintViolated, InvalidArgument, InvalidParameters
from mechkit.bench.sampling import make_samples
from mechkit.catalog.registry import specs
from mechkit.forces import JointSprings
from mechkit.mechanism_dynamics import MechanismDynamics
from mechkit.mechanism_naming import JointNaming


@pytest.mark.parametrize("overrides", [{"density": 1e-3}, {"density": 1e30}, "mm", "km"])
def test_forward_dynamics_scales_with_the_model(overrides, load_cached):
    base = load_cached("five_bar")
    lengths = ("ground", "prox1", "dist1", "prox2", "dist2", "width", "thickness")
    if overrides in ("mm", "km"):
        k = 1e-3 if overrides == "mm" else 1e3
        overrides = {n: getattr(base.params, n) * k for n in lengths}
    m = mechkit.load("five_bar", **overrides)
    q = m.home_q
    v = m.velocities(q, [1.0, -0.5])
    kkt = m.forward_dynamics(q, v, np.zeros(4), "kkt").a
    prox = m.forward_dynamics(q, v, np.zeros(4)).a
    J, gamma = m.closure_jacobian(q), m.closure_drift(q, v)
    assert np.max(np.abs(prox - kkt)) < 1e-9 * np.max(np.abs(kkt))
    assert np.max(np.abs(J @ kkt + gamma)) < 1e-10 * np.max(np.abs(J)) * np.max(np.abs(kkt))


def test_too_light_bodies_and_unconverged_results_are_refused(load_cached):
    with pytest.raises(InvalidParameters, match="mass of"):
        mechkit.load("five_bar", density=1e-12)
    m = load_cached("five_bar")
    v = m.velocities(m.home_q, [1.0, -0.5])
    with pytest.raises(ConstraintViolated, match="J a \\+ gamma"):
        m.forward_dynamics(m.home_q, v, np.zeros(4), mu=1e3, max_iter=1)


@pytest.mark.parametrize("name", list(specs()))
def test_supports_carry_weight_and_inertia(name, load_cached):
    """Newton's second law of the whole mechanism from the support reactions of the constrained RNEA."""
    m = load_cached(name)
    q = m.home_q
    v = np.zeros(m.model.nv)
    a = m.forward_dynamics(q, v, np.zeros(m.model.nv), "kkt").a  # free motion from rest under gravity
    assert support_balance_error(m, q, v, a) < 1e-9


def _dynamics(m, springs) -> MechanismDynamics:
    """A dynamics part over its own data, built from the mechanism's closure model alone."""
    cm = m.closure_model
    return MechanismDynamics(JointNaming(m.spec.name, cm), cm, cm.create_data(), springs, m.independent_rows, False)


@pytest.mark.parametrize("name,efforts", [("five_bar", (2.0, -1.5)), ("ten_bar", (2.0, -1.5))])
def test_forward_then_inverse_dynamics_return_the_efforts_given(name, efforts, load_cached):
    """Efforts u -> S^T u -> a (KKT forward dynamics, springs and dampers added) -> the efforts of the
    constrained RNEA (springs added again) = u, at a velocity of the closure's null space; the ten-bar's
    springs change a (so a side that dropped them would fail), and the facade gives the part's numbers."""
    m = load_cached(name)
    q = m.home_q
    null = scipy.linalg.null_space(m.closure_jacobian(q))
    v = null @ np.linspace(0.5, -0.7, null.shape[1])
    part = _dynamics(m, m.springs)
    u = dict(zip(m.actuated, efforts))
    tau = part.generalized_forces(u)
    a = part.forward_dynamics(q, v, tau, "kkt").a
    assert np.max(np.abs(m.closure_jacobian(q) @ a + m.closure_drift(q, v))) < 1e-11
    got = part.inverse_dynamics(q, v, a).efforts
    assert max(abs(got[j] - u[j]) for j in u) < 1e-10 * max(map(abs, efforts))
    np.testing.assert_array_equal(m.forward_dynamics(q, v, tau, "kkt").a, a)
    if m.springs:
        unsprung = _dynamics(m, JointSprings(m.model, ())).forward_dynamics(q, v, tau, "kkt").a
        assert np.max(np.abs(unsprung - a)) > 1e-3 * np.max(np.abs(a))


@pytest.mark.parametrize("sprung", [False, True])
def test_forward_dynamics_converts_or_names_what_is_not_a_float64_vector(sprung, load_cached):
    """The default method hands float64 vectors to Pinocchio unconverted (their sizes are its check): a
    list or another dtype gives the converted state's accelerations, a wrong size or a column a refusal
    naming the argument, with springs (computed before Pinocchio sees the state) or without."""
    m = load_cached("four_bar")
    springs = [core.JointSpring(m.model.names[1], 2.0, 0.0, 0.0, 0.1)] if sprung else []
    dyn = _dynamics(m, JointSprings(m.model, springs))
    s = make_samples(m, 1)[0]
    q, v, tau = s.q, s.v, s.tau
    a = dyn.forward_dynamics(q, v, tau).a
    for converted in ((q.tolist(), v, tau), (q, v, tau.tolist())):
        assert np.array_equal(dyn.forward_dynamics(*converted).a, a)
    single = tau.astype(np.float32)
    assert np.array_equal(dyn.forward_dynamics(q, v, single).a, dyn.forward_dynamics(q, v, single.astype(float)).a)
    for name, bad in (("q", (q[:-1], v, tau)), ("v", (q, np.append(v, 0.0), tau)), ("tau", (q, v, tau[:, None]))):
        with pytest.raises(InvalidArgument, match=f"argument '{name}'"):
            dyn.forward_dynamics(*bad)
