"""The public face of `mechkit.Mechanism` as a contract: every public method with its parameters (names,
kinds, defaults), its constructor, its public attributes and the private helpers the rest of the package
calls, as they were before `Mechanism` was composed of parts. A name or a parameter that disappears, is
renamed or changes its default fails here; a new public method must be added to the listing. And the
facade composed, not stacked: no inheritance, each method its part's own."""

from __future__ import annotations

import inspect

import pytest

import mechkit
from mechkit.mechanism_closure import MechanismClosure
from mechkit.mechanism_dynamics import MechanismDynamics
from mechkit.mechanism_naming import JointNaming
from mechkit.mechanism_rates import MechanismRates

FORWARD = "(q, v, tau, method='proximal', *, mu=None, accuracy=None, max_iter=None, baumgarte=None)"
INVERSE = "(q, v, a, fext=None, determinacy=True, distribution='min_norm', *, allow_singular=False)"
#: Method -> its parameters as the bound method shows them (annotations aside).
METHODS = {
    "accelerations": "(q, v, input_accelerations, inputs=None, *, allow_singular=False, least_squares=False)",
    "accelerations_batch": "(q, v, input_accelerations, inputs=None, *, allow_singular=False, least_squares=False)",
    "assemble": "(inputs, guess=None, *, tol=1e-12, method='newton', max_iter=60, reference=None)",
    "assembly": "(inputs, guess=None, *, tol=1e-12, method='newton', max_iter=60, reference=None)",
    "closure_drift": "(q, v)",
    "closure_jacobian": "(q)",
    "closure_residual": "(q)",
    "equilibrium": "(held=None, **options)",
    "forward_dynamics": FORWARD,
    "forward_dynamics_batch": FORWARD,
    "generalized_forces": "(efforts)",
    "inverse_dynamics": INVERSE,
    "inverse_dynamics_batch": INVERSE,
    "joint_id": "(joint)",
    "joint_values": "(q)",
    "mobility": "(q=None)",
    "neutral": "()",
    "passive_forces": "(q, v)",
    "q_index": "(joint)",
    "require_actuators": "(what)",
    "second_order_inconsistency": "(q, v)",
    "second_order_velocity": "(q, v)",
    "simulate": "(duration, **options)",
    "singularity": "(q, inputs=None)",
    "solve_closure": "(q0, fixed, *, tol=1e-12, max_iter=60, method='newton')",
    "v_index": "(joint)",
    "velocities": "(q, input_rates, inputs=None, *, allow_singular=False)",
    "velocities_batch": "(q, input_rates, inputs=None, *, allow_singular=False)",
}
#: Private helpers other modules of the package call (`mechkit.elastic.elastic_model`: state arrays checked).
PACKAGE_PRIVATE = {"_one": "(**values)", "_many": "(**values)"}
CONSTRUCTOR = "(spec, params, closure_model, urdf=None, springs=(), source_urdf=None)"
ATTRIBUTES = (
    "actuated",
    "closure_data",
    "closure_model",
    "closures",
    "cuts",
    "data",
    "home_assembly",
    "home_mobility",
    "home_q",
    "idle",
    "independent_rows",
    "model",
    "params",
    "source_urdf",
    "spec",
    "springs",
    "structure",
    "urdf",
)


def _parameters(fn) -> str:
    """A callable's parameters (names, kinds, defaults) without annotations."""
    sig = inspect.signature(fn)
    bare = [p.replace(annotation=p.empty) for p in sig.parameters.values()]
    return str(sig.replace(parameters=bare, return_annotation=sig.empty))


@pytest.fixture(scope="module")
def m(load_cached):
    return load_cached("four_bar")


def test_every_public_method_keeps_its_parameters(m):
    public = {
        n: _parameters(getattr(m, n)) for n in dir(m) if not n.startswith("_") and inspect.isroutine(getattr(m, n))
    }
    assert sorted(public) == sorted(METHODS), "a public method appeared or disappeared: update the listing on purpose"
    changed = {n: (public[n], METHODS[n]) for n in METHODS if public[n] != METHODS[n]}
    assert not changed, changed


def test_the_methods_read_on_the_class_are_documented_with_the_same_parameters():
    """help(mechkit.Mechanism.x) and the class's signatures: self first, then the listing; a docstring."""
    for name, params in {**METHODS, **PACKAGE_PRIVATE}.items():
        fn = getattr(mechkit.Mechanism, name)
        assert _parameters(fn) == "(self" + (", " if params != "()" else "") + params[1:], name
        assert (inspect.getdoc(fn) or "").strip(), name


def test_the_constructor_the_attributes_and_the_helpers_the_package_uses(m):
    assert _parameters(mechkit.Mechanism.__init__) == "(self, " + CONSTRUCTOR[1:]
    missing = [a for a in ATTRIBUTES if not hasattr(m, a)]
    assert not missing, missing
    assert {n: _parameters(getattr(m, n)) for n in PACKAGE_PRIVATE} == PACKAGE_PRIVATE
    (q,) = m._one(q=m.home_q)
    (qs,) = m._many(q=[m.home_q, m.home_q])
    assert q.shape == (m.model.nq,) and qs.shape == (2, m.model.nq)


def test_the_contract_sees_a_parameter_disappear():
    """The listing's own check: a method without one of its parameters, or with another default, differs."""

    def assembly(self, inputs, guess=None, *, tol=1e-12, method="newton", max_iter=60):
        """Without `reference`."""

    def mobility(self, q=0.0):
        """Another default."""

    assert _parameters(assembly) != "(self, " + METHODS["assembly"][1:]
    assert _parameters(mobility) != "(self, " + METHODS["mobility"][1:]


def test_the_mechanism_is_composed_of_parts_not_stacked(m):
    """No inheritance: the facade and each part derive from object alone, each part is built from what
    the facade hands it, and a public method read on a mechanism is its part's own bound method (nothing
    runs between the call and the part)."""
    parts = {"naming": JointNaming, "closure": MechanismClosure, "rates": MechanismRates, "dynamics": MechanismDynamics}
    assert mechkit.Mechanism.__mro__ == (mechkit.Mechanism, object)
    for attribute, cls in parts.items():
        assert cls.__mro__ == (cls, object) and type(getattr(m, attribute)) is cls
    answered = 0
    for name in METHODS:
        method = getattr(m, name)
        owner = [a for a in parts if getattr(method, "__self__", None) is getattr(m, a)]
        if owner:
            assert method == getattr(getattr(m, owner[0]), name)
            answered += 1
    assert answered == len(METHODS) - 2  # all but simulate and equilibrium, which call the simulator
