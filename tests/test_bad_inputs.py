"""The bad-input campaign over the API: every malformed argument of every public method is refused by a
named `MechkitError` subclass that names the argument, before any numerical work (no Pinocchio or
LAPACK error, no NaN); well-formed variants (lists, batches) give finite results that satisfy the
closure. Counts are in the README ("Bad input")."""

from __future__ import annotations

import numpy as np
import pytest

import mechkit
from mechkit.base.exceptions import (
    ClosureNotConverged,
    InvalidArgument,
    InvalidParameters,
    MalformedDescription,
    MechkitError,
    UnknownOption,
)

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
        "accelerations": {"q": lambda x: m.accelerations(x, z, [1.0, 0.5]), "v": lambda x: m.accelerations(q, x, [1.0, 0.5])},
        "mobility": {"q": lambda x: m.mobility(x)},
        "singularity": {"q": lambda x: m.singularity(x)},
        "forward_dynamics": {"q": lambda x: m.forward_dynamics(x, z, z), "v": lambda x: m.forward_dynamics(q, x, z),
                             "tau": lambda x: m.forward_dynamics(q, z, x)},
        "forward_dynamics_kkt": {"q": lambda x: m.forward_dynamics(x, z, z, "kkt"), "tau": lambda x: m.forward_dynamics(q, z, x, "kkt")},
        "inverse_dynamics": {"q": lambda x: m.inverse_dynamics(x, z, z), "v": lambda x: m.inverse_dynamics(q, x, z),
                             "a": lambda x: m.inverse_dynamics(q, z, x)},
    }


ARRAY_CASES = [(method, arg, kind) for method, args in {
    "closure_residual": ["q"], "closure_jacobian": ["q"], "closure_drift": ["q", "v"], "velocities": ["q"],
    "accelerations": ["q", "v"], "mobility": ["q"], "singularity": ["q"], "forward_dynamics": ["q", "v", "tau"],
    "forward_dynamics_kkt": ["q", "tau"], "inverse_dynamics": ["q", "v", "a"]}.items()
    for arg in args for kind in BAD_VECTORS if not (method == "mobility" and kind == "none")]  # None: home


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
        "assemble-guess-nan": (lambda: m.assemble([2.0, 1.1], guess=np.full(m.model.nq, np.nan)), InvalidArgument, "guess"),
        "assemble-guess-shape": (lambda: m.assemble([2.0, 1.1], guess=np.zeros(3)), InvalidArgument, "guess"),
        "assemble-guess-string": (lambda: m.assemble([2.0, 1.1], guess="home"), InvalidArgument, "guess"),
        "velocities-rates-nan": (lambda: m.velocities(q, [np.nan, 1.0]), InvalidArgument, "input_rates"),
        "velocities-rates-count": (lambda: m.velocities(q, [1.0, 2.0, 3.0]), InvalidArgument, "input_rates"),
        "velocities-inputs-unknown": (lambda: m.velocities(q, [1.0, 2.0], inputs=["nope", "prox2"]), InvalidArgument, "inputs"),
        "velocities-inputs-repeated": (lambda: m.velocities(q, [1.0, 2.0], inputs=["prox1", "prox1"]), InvalidArgument, "inputs"),
        "velocities-inputs-string": (lambda: m.velocities(q, [1.0], inputs="prox1"), InvalidArgument, "inputs"),
        "velocities-allow-singular-string": (lambda: m.velocities(q, [1.0, 2.0], allow_singular="yes"), InvalidArgument, "allow_singular"),
        "accelerations-nan": (lambda: m.accelerations(q, z, [np.inf, 1.0]), InvalidArgument, "input_accelerations"),
        "forward-method-bogus": (lambda: m.forward_dynamics(q, z, z, "bogus"), UnknownOption, "method"),
        "forward-method-bogus-bad-q": (lambda: m.forward_dynamics(None, z, z, "bogus"), UnknownOption, "method"),
        "forward-mu-negative": (lambda: m.forward_dynamics(q, z, z, mu=-1.0), InvalidArgument, "mu"),
        "forward-mu-nan": (lambda: m.forward_dynamics(q, z, z, mu=float("nan")), InvalidArgument, "mu"),
        "forward-mu-string": (lambda: m.forward_dynamics(q, z, z, mu="small"), InvalidArgument, "mu"),
        "forward-accuracy-zero": (lambda: m.forward_dynamics(q, z, z, accuracy=0.0), InvalidArgument, "accuracy"),
        "forward-max-iter-zero": (lambda: m.forward_dynamics(q, z, z, max_iter=0), InvalidArgument, "max_iter"),
        "forward-baumgarte-short": (lambda: m.forward_dynamics(q, z, z, baumgarte=(1.0,)), InvalidArgument, "baumgarte"),
        "forward-baumgarte-nan": (lambda: m.forward_dynamics(q, z, z, "kkt", baumgarte=(np.nan, 1.0)), InvalidArgument, "baumgarte"),
        "forward-kkt-mu-checked-too": (lambda: m.forward_dynamics(q, z, z, "kkt", mu=-1.0), InvalidArgument, "mu"),
        "inverse-distribution-bogus": (lambda: m.inverse_dynamics(q, z, a, distribution="bogus"), UnknownOption, "distribution"),
        "inverse-distribution-bogus-fast-path": (lambda: m.inverse_dynamics(q, z, a, determinacy=False, distribution="bogus"),
                                                 UnknownOption, "distribution"),
        "inverse-determinacy-string": (lambda: m.inverse_dynamics(q, z, a, determinacy="False"), InvalidArgument, "determinacy"),
        "inverse-fext-list-of-numbers": (lambda: m.inverse_dynamics(q, z, a, fext=[1, 2, 3]), InvalidArgument, "fext"),
        "inverse-fext-count": (lambda: m.inverse_dynamics(q, z, a, fext=np.zeros((2, 6))), InvalidArgument, "fext"),
        "inverse-fext-nan": (lambda: m.inverse_dynamics(q, z, a, fext=np.full((m.model.njoints, 6), np.nan)), InvalidArgument, "fext"),
        "inverse-fext-string": (lambda: m.inverse_dynamics(q, z, a, fext="thrust"), InvalidArgument, "fext"),
        "inverse-state-batch-mismatch": (lambda: m.inverse_dynamics_batch(np.stack([q, q]), np.stack([z, z, z]), np.stack([a, a])),
                                         InvalidArgument, "q, v, a"),
        "inverse-batch-to-one-sample": (lambda: m.inverse_dynamics(np.stack([q, q]), z, a), InvalidArgument, "_batch"),
        "velocities-batch-without-axis": (lambda: m.velocities_batch(q, [1.0, 0.0]), InvalidArgument, "without _batch"),
        "q-index-none": (lambda: m.q_index(None), InvalidParameters, "joint"),
        "v-index-unknown": (lambda: m.v_index("nope"), InvalidParameters, "joint"),
        "singularity-inputs-unknown": (lambda: m.singularity(q, ["nope"]), InvalidArgument, "inputs"),
    }


@pytest.mark.parametrize("case", [
    "assemble-method-bogus", "assemble-method-none", "assemble-tol-negative", "assemble-tol-nan", "assemble-max-iter-zero",
    "assemble-max-iter-float", "assemble-inputs-nan", "assemble-inputs-count", "assemble-inputs-string",
    "assemble-inputs-unknown-joint", "assemble-inputs-mapping-nan", "assemble-guess-nan", "assemble-guess-shape",
    "assemble-guess-string", "velocities-rates-nan", "velocities-rates-count", "velocities-inputs-unknown",
    "velocities-inputs-repeated", "velocities-inputs-string", "velocities-allow-singular-string", "accelerations-nan",
    "forward-method-bogus", "forward-method-bogus-bad-q", "forward-mu-negative", "forward-mu-nan", "forward-mu-string",
    "forward-accuracy-zero", "forward-max-iter-zero", "forward-baumgarte-short", "forward-baumgarte-nan",
    "forward-kkt-mu-checked-too", "inverse-distribution-bogus", "inverse-distribution-bogus-fast-path",
    "inverse-determinacy-string", "inverse-fext-list-of-numbers", "inverse-fext-count", "inverse-fext-nan",
    "inverse-fext-string", "inverse-state-batch-mismatch", "inverse-batch-to-one-sample",
    "velocities-batch-without-axis", "q-index-none", "v-index-unknown", "singularity-inputs-unknown"])
def test_bad_options_and_scalars_are_refused_by_name(m, case, capfd):
    call, kind, name = _option_cases(m)[case]
    with pytest.raises(kind) as err:
        call()
    assert name in str(err.value)
    assert capfd.readouterr().err == ""


LOAD_CASES = {
    "name-none": ((None,), {}, InvalidArgument),
    "name-number": ((123,), {}, InvalidArgument),
    "name-unknown": (("nope",), {}, InvalidParameters),
    "param-unknown": ((NAME,), {"bogus": 1.0}, InvalidParameters),
    "param-nan": ((NAME,), {"prox1": float("nan")}, InvalidParameters),
    "param-inf": ((NAME,), {"prox1": float("inf")}, InvalidParameters),
    "param-negative-length": ((NAME,), {"prox1": -0.1}, InvalidParameters),
    "param-zero-density": ((NAME,), {"density": 0.0}, InvalidParameters),
    "param-string": ((NAME,), {"prox1": "long"}, InvalidParameters),
    "density-below-pinocchio-epsilon": ((NAME,), {"density": 1e-12}, InvalidParameters),
    "cannot-assemble": ((NAME,), {"dist1": 0.01, "dist2": 0.01}, (ClosureNotConverged, InvalidParameters)),
    "actuated-unknown": ((NAME,), {"actuated": ["nope"]}, MechkitError),
}


@pytest.mark.parametrize("case", list(LOAD_CASES))
def test_load_refuses_bad_names_and_parameters(case):
    args, kwargs, kind = LOAD_CASES[case]
    with pytest.raises(kind):
        mechkit.load(*args, **kwargs)


@pytest.mark.parametrize("urdf,kind", [(None, InvalidArgument), ("", InvalidArgument), (42, InvalidArgument),
                                       ("<robot name='x'><link name='a'/>", MalformedDescription),
                                       ("/no/such/file.urdf", MalformedDescription)])
def test_from_urdf_refuses_what_is_not_urdf(urdf, kind):
    with pytest.raises(kind):
        mechkit.from_urdf(urdf)


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
