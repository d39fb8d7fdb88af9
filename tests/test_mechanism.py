"""`mechkit.mechanism.Mechanism` through its public methods: the bad-input campaign (every malformed
argument refused by a named `MechkitError` that names it, before any numerical work; well-formed
variants give finite results that satisfy the closure; counts in the README, "Bad input"), singularity
judged against what the closure resolves, and the planar linkages from assembly to every pin reaction
against their independent closed-form references (the public face itself: tests/test_mechanism_api.py;
the dynamics at any scale and Newton's law from the supports: tests/test_mechanism_dynamics.py)."""

from __future__ import annotations

import numpy as np
import pytest
from tests_support import DISTANCES, singular_inputs

import mechkit
from mechkit.base.exceptions import (
    InvalidArgument,
    InvalidParameters,
    SingularConfiguration,
    UnknownOption,
)
from mechkit.validation.planar_closed_form import five_bar, four_bar
from mechkit.validation.planar_newton_euler import newton_euler

NAME = "five_bar"


@pytest.fixture(scope="module")
def m(load_cached):
    return load_cached(NAME)


BAD_VECTORS = {
    "none": None,
    "string": "abc",
    "short": [0.1, 0.2],
    "nan": "NAN",
    "inf": "INF",
    "complex": "COMPLEX",
    "three_d": "3D",
    "ragged": [[0.0, 1.0], [0.0]],
    "mapping": {"a": 1.0},
}


def _bad(kind: str, n: int):
    value = BAD_VECTORS[kind]
    if value == "NAN":
        return np.full(n, np.nan)
    if value == "INF":
        return np.r_[np.inf, np.zeros(n - 1)]
    if value == "COMPLEX":
        return np.zeros(n, dtype=complex)
    if value == "3D":
        return np.zeros((2, 2, n))
    return value


def _calls(m):
    """Public methods as (name, argument name -> builder of the call with that argument replaced)."""
    q, z = m.home_q, np.zeros(m.model.nv)
    return {
        "closure_residual": {"q": lambda x: m.closure_residual(x)},
        "closure_jacobian": {"q": lambda x: m.closure_jacobian(x)},
        "closure_drift": {"q": lambda x: m.closure_drift(x, z), "v": lambda x: m.closure_drift(q, x)},
        "velocities": {"q": lambda x: m.velocities(x, [1.0, 0.5])},
        "accelerations": {
            "q": lambda x: m.accelerations(x, z, [1.0, 0.5]),
            "v": lambda x: m.accelerations(q, x, [1.0, 0.5]),
        },
        "mobility": {"q": lambda x: m.mobility(x)},
        "singularity": {"q": lambda x: m.singularity(x)},
        "forward_dynamics": {
            "q": lambda x: m.forward_dynamics(x, z, z),
            "v": lambda x: m.forward_dynamics(q, x, z),
            "tau": lambda x: m.forward_dynamics(q, z, x),
        },
        "forward_dynamics_kkt": {
            "q": lambda x: m.forward_dynamics(x, z, z, "kkt"),
            "tau": lambda x: m.forward_dynamics(q, z, x, "kkt"),
        },
        "inverse_dynamics": {
            "q": lambda x: m.inverse_dynamics(x, z, z),
            "v": lambda x: m.inverse_dynamics(q, x, z),
            "a": lambda x: m.inverse_dynamics(q, z, x),
        },
    }


ARRAY_CASES = [
    (method, arg, kind)
    for method, args in {
        "closure_residual": ["q"],
        "closure_jacobian": ["q"],
        "closure_drift": ["q", "v"],
        "velocities": ["q"],
        "accelerations": ["q", "v"],
        "mobility": ["q"],
        "singularity": ["q"],
        "forward_dynamics": ["q", "v", "tau"],
        "forward_dynamics_kkt": ["q", "tau"],
        "inverse_dynamics": ["q", "v", "a"],
    }.items()
    for arg in args
    for kind in BAD_VECTORS
    if not (method == "mobility" and kind == "none")
]  # None: home


@pytest.mark.parametrize("method,arg,kind", ARRAY_CASES, ids=[f"{a}-{b}-{c}" for a, b, c in ARRAY_CASES])
def test_malformed_state_arrays_are_refused_by_name(m, method, arg, kind, capfd):
    n = m.model.nq if arg == "q" else m.model.nv
    with pytest.raises(InvalidArgument) as err:
        _calls(m)[method][arg](_bad(kind, n))
    assert repr(arg) in str(err.value)
    assert capfd.readouterr().err == ""  # nothing from LAPACK or Pinocchio on stderr


def _option_cases(m):
    q, z = m.home_q, np.zeros(m.model.nv)
    a = m.forward_dynamics(q, z, z, "kkt").a
    return {
        "assemble-method-bogus": (lambda: m.assemble([2.0, 1.1], method="bogus"), UnknownOption, "method"),
        "assemble-method-none": (lambda: m.assemble([2.0, 1.1], method=None), UnknownOption, "method"),
        "assemble-tol-negative": (lambda: m.assemble([2.0, 1.1], tol=-1.0), InvalidArgument, "tol"),
        "assemble-tol-nan": (lambda: m.assemble([2.0, 1.1], tol=float("nan")), InvalidArgument, "tol"),
        "assemble-max-iter-zero": (lambda: m.assemble([2.0, 1.1], max_iter=0), InvalidArgument, "max_iter"),
        "assemble-max-iter-float": (lambda: m.assemble([2.0, 1.1], max_iter=2.5), InvalidArgument, "max_iter"),
        "assemble-inputs-nan": (lambda: m.assemble([np.nan, 1.1]), InvalidArgument, "inputs"),
        "assemble-inputs-count": (lambda: m.assemble([2.0]), InvalidArgument, "inputs"),
        "assemble-inputs-string": (lambda: m.assemble("2.0, 1.1"), InvalidArgument, "inputs"),
        "assemble-inputs-unknown-joint": (lambda: m.assemble({"nope": 1.0}), InvalidArgument, "inputs"),
        "assemble-inputs-mapping-nan": (lambda: m.assemble({"prox1": np.nan, "prox2": 1.1}), InvalidArgument, "prox1"),
        "assemble-guess-nan": (
            lambda: m.assemble([2.0, 1.1], guess=np.full(m.model.nq, np.nan)),
            InvalidArgument,
            "guess",
        ),
        "assemble-guess-shape": (lambda: m.assemble([2.0, 1.1], guess=np.zeros(3)), InvalidArgument, "guess"),
        "assemble-guess-string": (lambda: m.assemble([2.0, 1.1], guess="home"), InvalidArgument, "guess"),
        "velocities-rates-nan": (lambda: m.velocities(q, [np.nan, 1.0]), InvalidArgument, "input_rates"),
        "velocities-rates-count": (lambda: m.velocities(q, [1.0, 2.0, 3.0]), InvalidArgument, "input_rates"),
        "velocities-inputs-unknown": (
            lambda: m.velocities(q, [1.0, 2.0], inputs=["nope", "prox2"]),
            InvalidArgument,
            "inputs",
        ),
        "velocities-inputs-repeated": (
            lambda: m.velocities(q, [1.0, 2.0], inputs=["prox1", "prox1"]),
            InvalidArgument,
            "inputs",
        ),
        "velocities-inputs-string": (lambda: m.velocities(q, [1.0], inputs="prox1"), InvalidArgument, "inputs"),
        "velocities-allow-singular-string": (
            lambda: m.velocities(q, [1.0, 2.0], allow_singular="yes"),
            InvalidArgument,
            "allow_singular",
        ),
        "accelerations-nan": (lambda: m.accelerations(q, z, [np.inf, 1.0]), InvalidArgument, "input_accelerations"),
        "forward-method-bogus": (lambda: m.forward_dynamics(q, z, z, "bogus"), UnknownOption, "method"),
        "forward-method-bogus-bad-q": (lambda: m.forward_dynamics(None, z, z, "bogus"), UnknownOption, "method"),
        "forward-mu-negative": (lambda: m.forward_dynamics(q, z, z, mu=-1.0), InvalidArgument, "mu"),
        "forward-mu-nan": (lambda: m.forward_dynamics(q, z, z, mu=float("nan")), InvalidArgument, "mu"),
        "forward-mu-string": (lambda: m.forward_dynamics(q, z, z, mu="small"), InvalidArgument, "mu"),
        "forward-accuracy-zero": (lambda: m.forward_dynamics(q, z, z, accuracy=0.0), InvalidArgument, "accuracy"),
        "forward-max-iter-zero": (lambda: m.forward_dynamics(q, z, z, max_iter=0), InvalidArgument, "max_iter"),
        "forward-baumgarte-short": (
            lambda: m.forward_dynamics(q, z, z, baumgarte=(1.0,)),
            InvalidArgument,
            "baumgarte",
        ),
        "forward-baumgarte-nan": (
            lambda: m.forward_dynamics(q, z, z, "kkt", baumgarte=(np.nan, 1.0)),
            InvalidArgument,
            "baumgarte",
        ),
        "forward-kkt-mu-checked-too": (lambda: m.forward_dynamics(q, z, z, "kkt", mu=-1.0), InvalidArgument, "mu"),
        "inverse-distribution-bogus": (
            lambda: m.inverse_dynamics(q, z, a, distribution="bogus"),
            UnknownOption,
            "distribution",
        ),
        "inverse-distribution-bogus-fast-path": (
            lambda: m.inverse_dynamics(q, z, a, determinacy=False, distribution="bogus"),
            UnknownOption,
            "distribution",
        ),
        "inverse-determinacy-string": (
            lambda: m.inverse_dynamics(q, z, a, determinacy="False"),
            InvalidArgument,
            "determinacy",
        ),
        "inverse-fext-list-of-numbers": (lambda: m.inverse_dynamics(q, z, a, fext=[1, 2, 3]), InvalidArgument, "fext"),
        "inverse-fext-count": (lambda: m.inverse_dynamics(q, z, a, fext=np.zeros((2, 6))), InvalidArgument, "fext"),
        "inverse-fext-nan": (
            lambda: m.inverse_dynamics(q, z, a, fext=np.full((m.model.njoints, 6), np.nan)),
            InvalidArgument,
            "fext",
        ),
        "inverse-fext-string": (lambda: m.inverse_dynamics(q, z, a, fext="thrust"), InvalidArgument, "fext"),
        "inverse-state-batch-mismatch": (
            lambda: m.inverse_dynamics_batch(np.stack([q, q]), np.stack([z, z, z]), np.stack([a, a])),
            InvalidArgument,
            "q, v, a",
        ),
        "inverse-batch-to-one-sample": (lambda: m.inverse_dynamics(np.stack([q, q]), z, a), InvalidArgument, "_batch"),
        "velocities-batch-without-axis": (lambda: m.velocities_batch(q, [1.0, 0.0]), InvalidArgument, "without _batch"),
        "q-index-none": (lambda: m.q_index(None), InvalidParameters, "joint"),
        "v-index-unknown": (lambda: m.v_index("nope"), InvalidParameters, "joint"),
        "singularity-inputs-unknown": (lambda: m.singularity(q, ["nope"]), InvalidArgument, "inputs"),
    }


@pytest.mark.parametrize(
    "case",
    [
        "assemble-method-bogus",
        "assemble-method-none",
        "assemble-tol-negative",
        "assemble-tol-nan",
        "assemble-max-iter-zero",
        "assemble-max-iter-float",
        "assemble-inputs-nan",
        "assemble-inputs-count",
        "assemble-inputs-string",
        "assemble-inputs-unknown-joint",
        "assemble-inputs-mapping-nan",
        "assemble-guess-nan",
        "assemble-guess-shape",
        "assemble-guess-string",
        "velocities-rates-nan",
        "velocities-rates-count",
        "velocities-inputs-unknown",
        "velocities-inputs-repeated",
        "velocities-inputs-string",
        "velocities-allow-singular-string",
        "accelerations-nan",
        "forward-method-bogus",
        "forward-method-bogus-bad-q",
        "forward-mu-negative",
        "forward-mu-nan",
        "forward-mu-string",
        "forward-accuracy-zero",
        "forward-max-iter-zero",
        "forward-baumgarte-short",
        "forward-baumgarte-nan",
        "forward-kkt-mu-checked-too",
        "inverse-distribution-bogus",
        "inverse-distribution-bogus-fast-path",
        "inverse-determinacy-string",
        "inverse-fext-list-of-numbers",
        "inverse-fext-count",
        "inverse-fext-nan",
        "inverse-fext-string",
        "inverse-state-batch-mismatch",
        "inverse-batch-to-one-sample",
        "velocities-batch-without-axis",
        "q-index-none",
        "v-index-unknown",
        "singularity-inputs-unknown",
    ],
)
def test_bad_options_and_scalars_are_refused_by_name(m, case, capfd):
    call, kind, name = _option_cases(m)[case]
    with pytest.raises(kind) as err:
        call()
    assert name in str(err.value)
    assert capfd.readouterr().err == ""


def test_well_formed_variants_give_finite_checked_results(m):
    """Lists for arrays, mappings for inputs and a batch of two give the same finite results."""
    q = m.home_q
    J = m.closure_jacobian(list(q))
    v = m.velocities(list(q), {"prox1": 1.0, "prox2": -0.5})
    assert np.all(np.isfinite(v)) and np.max(np.abs(J @ v)) < 1e-12 and np.isfinite(m.singularity(q))
    a = m.accelerations(q, v, (0.3, 0.1))
    assert np.max(np.abs(J @ a + m.closure_drift(q, v))) < 1e-10
    fd = m.forward_dynamics(list(q), list(v), [0.0] * m.model.nv)
    assert np.all(np.isfinite(fd.a))
    both = m.forward_dynamics_batch(np.stack([q, q]), np.stack([v, v]), np.zeros((2, m.model.nv)), "kkt")
    assert np.allclose(both.a[0], fd.a, rtol=1e-9, atol=1e-9)
    fext = np.zeros((m.model.njoints, 6))
    assert m.inverse_dynamics(q, v, a, fext=fext).efforts == pytest.approx(m.inverse_dynamics(q, v, a).efforts)


def test_calibration_distance_to_the_singular_input_against_condition_number(load_cached):
    m = load_cached("five_bar")
    for root, side in singular_inputs(m):
        conds, caught = [], []
        for d in DISTANCES:
            q = m.assemble({"prox1": 2.6, "prox2": root + side * d}, guess=m.home_q)
            conds.append(m.singularity(q))
            try:
                v = m.velocities(q, [1.0, 1.0])
                caught.append(False)
                assert np.isfinite(conds[-1]) and np.max(np.abs(m.closure_jacobian(q) @ v)) < 1e-9 * np.max(np.abs(v))
            except SingularConfiguration:
                caught.append(True)
                with pytest.raises(SingularConfiguration):
                    m.inverse_dynamics(q, np.zeros(4), np.zeros(4))
                v = m.velocities(q, [1.0, 1.0], allow_singular=True)
                assert np.all(np.isfinite(v)) and np.isfinite(conds[-1])
        # caught at the singular input and within 1e-11 rad of it; regular from 1e-10 rad on
        assert caught == [d <= 1e-11 for d in DISTANCES], list(zip(DISTANCES, caught, conds))
        # condition ~ 1/sqrt(d) away from the rounding floor (the collinear pose of the issue: ~6e5-9e5)
        slope = np.polyfit(np.log(DISTANCES[6:]), np.log(conds[6:]), 1)[0]
        assert slope == pytest.approx(-0.5, abs=0.02)
        assert 3e5 < conds[0] < 2e6


def test_a_linkage_that_cannot_assemble_is_a_clear_error():
    # crank at pi puts B 0.55 m from D: coupler + rocker (0.28 + 0.22) cannot reach
    m = mechkit.load("four_bar", ground=0.45)
    with pytest.raises(mechkit.ClosureNotConverged) as err:
        m.assemble([np.pi])
    assert err.value.residual > err.value.tol


T = np.linspace(0.0, 2.0, 41)


def crank_law(t):
    """A smooth crank motion covering more than a full turn: angle, rate, acceleration."""
    return 0.6 + 4.0 * t + 0.3 * np.sin(3 * t), 4.0 + 0.9 * np.cos(3 * t), -2.7 * np.sin(3 * t)


def five_bar_law(t):
    th = np.array([2.0 + 0.3 * np.sin(2 * t), 1.1 + 0.25 * np.sin(3 * t + 0.4)])
    rate = np.array([0.6 * np.cos(2 * t), 0.75 * np.cos(3 * t + 0.4)])
    acc = np.array([-1.2 * np.sin(2 * t), -2.25 * np.sin(3 * t + 0.4)])
    return th, rate, acc


def _wrap(x):
    return (x + np.pi) % (2 * np.pi) - np.pi


def _samples(name, load_cached):
    m = load_cached(name)
    q = m.home_q
    for t in T:
        if name == "four_bar":
            th, rate, acc = crank_law(t)
            state = four_bar(th, rate, acc)
        else:
            th, rate, acc = five_bar_law(t)
            state = five_bar(tuple(th), tuple(rate), tuple(acc))
        q = m.assemble(np.atleast_1d(th), guess=q)
        v = m.velocities(q, np.atleast_1d(rate))
        a = m.accelerations(q, v, np.atleast_1d(acc))
        yield m, state, q, v, a


@pytest.mark.parametrize("name", ["four_bar", "five_bar"])
def test_kinematics_match_closed_form(name, load_cached):
    for m, state, q, v, a in _samples(name, load_cached):
        order = [m.q_index(j) for j in state.coordinates]
        assert np.max(np.abs(_wrap(q[order] - state.q))) < 1e-10
        assert np.max(np.abs(v[order] - state.qd)) < 1e-10 * max(1.0, np.max(np.abs(state.qd)))
        assert np.max(np.abs(a[order] - state.qdd)) < 1e-10 * max(1.0, np.max(np.abs(state.qdd)))


@pytest.mark.parametrize("name", ["four_bar", "five_bar"])
def test_torques_and_every_pin_reaction_match_newton_euler(name, load_cached):
    worst = 0.0
    for m, state, q, v, a in _samples(name, load_cached):
        expected = newton_euler(state)
        got = m.inverse_dynamics(q, v, a)
        scale = max(np.max(np.abs(w)) for w in expected.reactions.values())
        assert set(got.reactions) == set(expected.reactions)
        for joint, wrench in expected.reactions.items():
            r = got.reactions[joint]
            # in-plane forces and the moment about the axis are determinate; compare those
            np.testing.assert_array_equal(r.determinate, [True, False, True, False, True, False])
            worst = max(worst, np.max(np.abs(r.wrench[[0, 2, 4]] - wrench[[0, 2, 4]])) / scale)
        for joint, effort in expected.efforts.items():
            worst = max(worst, abs(got.efforts[joint] - effort) / scale)
    assert worst < 1e-9
