"""`Mechanism`: one closed-loop mechanism, a facade of one-liners over the parts it holds.

Its construction builds the closure model's data once (scratch) and composes four parts, each a class
with its own state that needs nothing from the facade: the joints and actuators by name
(`mechkit.mechanism_naming.JointNaming`), the closure (`mechkit.mechanism_closure.MechanismClosure`:
home assembly, assembly, closure rows, mobility, singularity), the velocities and accelerations from the
inputs (`mechkit.mechanism_rates.MechanismRates`) and the dynamics (`mechkit.mechanism_dynamics.
MechanismDynamics`: forward and inverse, one sample or N, generalised and passive forces). Each public
method is one part's method (its signature and docstring); the motion in time is the simulator's.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Any, Concatenate, Generic, ParamSpec, TypeVar, overload

from mechkit import core
from mechkit.catalog.contract import MechanismSpec
from mechkit.catalog.params import MechanismParams
from mechkit.forces import JointSprings
from mechkit.mechanism_closure import MechanismClosure
from mechkit.mechanism_dynamics import MechanismDynamics
from mechkit.mechanism_naming import JointNaming
from mechkit.mechanism_rates import MechanismRates

P = ParamSpec("P")
R = TypeVar("R")


class _AnsweredBy(Generic[P, R]):
    """A method of `Mechanism` that one of its parts answers.

    Read on the class, it is the part's function (its signature and docstring: `help`, `inspect`); read
    on a mechanism, the part's bound method, kept in the mechanism's `__dict__` at first use so that later
    calls go straight to the part (no call in between).
    """

    def __init__(self, part: str, method: Callable[Concatenate[Any, P], R]):
        self.part, self.method = part, method

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    @overload
    def __get__(self, mechanism: None, owner: type) -> Callable[Concatenate[Any, P], R]: ...
    @overload
    def __get__(self, mechanism: Mechanism, owner: type) -> Callable[P, R]: ...
    def __get__(self, mechanism: Mechanism | None, owner: type) -> Callable[..., R]:
        if mechanism is None:
            return self.method
        bound = getattr(getattr(mechanism, self.part), self.method.__name__)
        mechanism.__dict__[self.name] = bound
        return bound


class Mechanism:
    """A closed-loop mechanism: a Pinocchio tree (any joints), its closures and couplings, its actuators.

    Each public method is its part's own, named beside it below (`simulate` and `equilibrium` call the
    simulator); `closure` is the part, `closures` the loops' records.

    Args:
        spec: the registry entry (or the one a file reader made).
        params: the parameter values used.
        closure_model: the tree with its closures, couplings and actuation (`mechkit.core.ClosureModel`).
        urdf: the tree's URDF text, where it has one (None: its joints are not URDF's).
        springs: joint springs and dampers (passive forces in the dynamics, `mechkit.forces.JointSprings`).
        source_urdf: the URDF it was reduced from (`mechkit.reduction`), when `urdf` is None: its elements
            that name links and joints (beams, elastic joints) still apply to the mechanism.

    Attributes:
        naming, closure, rates, dynamics: its parts (`JointNaming`, `MechanismClosure`, `MechanismRates`,
            `MechanismDynamics`).
        model, data: the Pinocchio model of the tree and a data for it (scratch, the parts' too).
        closure_model, closure_data: the closure model and its data.
        closures, structure, actuated: as the closure model's. springs: the joint springs and dampers.
        home_q: the home assembly; home_assembly: its record (the branch it took, the joints it leaves
            outside their limits); home_mobility: the mobility at home; independent_rows: its rank (the
            closure's generic rank); idle: body -> idle freedoms at home (`mechkit.core.idle_freedoms`).

    Raises:
        ClosureNotConverged, SingularConfiguration: the home assembly cannot be found.
    """

    def __init__(
        self,
        spec: MechanismSpec,
        params: MechanismParams,
        closure_model: core.ClosureModel,
        urdf: str | None = None,
        springs: Sequence[core.JointSpring] = (),
        source_urdf: str | None = None,
    ):
        self.spec, self.params, self.urdf, self.source_urdf = spec, params, urdf, source_urdf
        self.closure_model = cm = closure_model
        self.closure_data = cd = cm.create_data()
        self.model, self.data = cm.model, cd.pin
        self.structure, self.closures, self.actuated = cm.structure, list(cm.closures), cm.actuated
        self.springs = JointSprings(self.model, springs, cuts=cm.kernel.cuts)
        self.naming = JointNaming(spec.name, cm, urdf)
        self.closure = closure = MechanismClosure(self.naming, cm, cd, spec, params)
        self.home_assembly, self.home_q = closure.home_assembly, closure.home_q
        self.home_mobility, self.independent_rows = closure.home_mobility, closure.independent_rows
        self.idle = closure.idle
        self.rates = MechanismRates(self.naming, cm, cd)
        self.dynamics = MechanismDynamics(self.naming, cm, cd, self.springs, self.independent_rows, bool(self.idle))

    def __repr__(self) -> str:
        """One line: name, coordinates, degrees of freedom, loops, actuators."""
        return (
            f"<Mechanism {self.spec.name}: nq={self.model.nq}, dof={self.home_mobility.dof}, "
            f"loops={len(self.closures)}, actuators={list(self.actuated)}>"
        )

    @property
    def cuts(self) -> tuple:
        """The closures' kept rows (`CutRows`: closure, frame ids, directions), in closure order."""
        return self.closure_model.kernel.cuts

    # ---------------------------------------------------------------- joints by name
    joint_id = _AnsweredBy("naming", JointNaming.joint_id)
    """[`JointNaming.joint_id`][mechkit.mechanism_naming.JointNaming.joint_id]."""
    q_index = _AnsweredBy("naming", JointNaming.q_index)
    """[`JointNaming.q_index`][mechkit.mechanism_naming.JointNaming.q_index]."""
    v_index = _AnsweredBy("naming", JointNaming.v_index)
    """[`JointNaming.v_index`][mechkit.mechanism_naming.JointNaming.v_index]."""
    neutral = _AnsweredBy("naming", JointNaming.neutral)
    """[`JointNaming.neutral`][mechkit.mechanism_naming.JointNaming.neutral]."""
    joint_values = _AnsweredBy("naming", JointNaming.joint_values)
    """[`JointNaming.joint_values`][mechkit.mechanism_naming.JointNaming.joint_values]."""
    require_actuators = _AnsweredBy("naming", JointNaming.require_actuators)
    """[`JointNaming.require_actuators`][mechkit.mechanism_naming.JointNaming.require_actuators]."""
    _one = _AnsweredBy("naming", JointNaming.one)  # state arrays checked, as mechkit.elastic calls them
    _many = _AnsweredBy("naming", JointNaming.many)

    # ---------------------------------------------------------------- the closure
    assemble = _AnsweredBy("closure", MechanismClosure.assemble)
    """[`MechanismClosure.assemble`][mechkit.mechanism_closure.MechanismClosure.assemble]."""
    assembly = _AnsweredBy("closure", MechanismClosure.assembly)
    """[`MechanismClosure.assembly`][mechkit.mechanism_closure.MechanismClosure.assembly]."""
    solve_closure = _AnsweredBy("closure", MechanismClosure.solve_closure)
    """[`MechanismClosure.solve_closure`][mechkit.mechanism_closure.MechanismClosure.solve_closure]."""
    closure_residual = _AnsweredBy("closure", MechanismClosure.closure_residual)
    """[`MechanismClosure.closure_residual`][mechkit.mechanism_closure.MechanismClosure.closure_residual]."""
    closure_jacobian = _AnsweredBy("closure", MechanismClosure.closure_jacobian)
    """[`MechanismClosure.closure_jacobian`][mechkit.mechanism_closure.MechanismClosure.closure_jacobian]."""
    closure_drift = _AnsweredBy("closure", MechanismClosure.closure_drift)
    """[`MechanismClosure.closure_drift`][mechkit.mechanism_closure.MechanismClosure.closure_drift]."""
    mobility = _AnsweredBy("closure", MechanismClosure.mobility)
    """[`MechanismClosure.mobility`][mechkit.mechanism_closure.MechanismClosure.mobility]."""
    singularity = _AnsweredBy("closure", MechanismClosure.singularity)
    """[`MechanismClosure.singularity`][mechkit.mechanism_closure.MechanismClosure.singularity]."""

    # ---------------------------------------------------------------- velocities and accelerations
    velocities = _AnsweredBy("rates", MechanismRates.velocities)
    """[`MechanismRates.velocities`][mechkit.mechanism_rates.MechanismRates.velocities]."""
    velocities_batch = _AnsweredBy("rates", MechanismRates.velocities_batch)
    """[`MechanismRates.velocities_batch`][mechkit.mechanism_rates.MechanismRates.velocities_batch]."""
    accelerations = _AnsweredBy("rates", MechanismRates.accelerations)
    """[`MechanismRates.accelerations`][mechkit.mechanism_rates.MechanismRates.accelerations]."""
    accelerations_batch = _AnsweredBy("rates", MechanismRates.accelerations_batch)
    """[`MechanismRates.accelerations_batch`][mechkit.mechanism_rates.MechanismRates.accelerations_batch]."""
    second_order_inconsistency = _AnsweredBy("rates", MechanismRates.second_order_inconsistency)
    """[`MechanismRates.second_order_inconsistency`][mechkit.mechanism_rates.MechanismRates.second_order_inconsistency]."""
    second_order_velocity = _AnsweredBy("rates", MechanismRates.second_order_velocity)
    """[`MechanismRates.second_order_velocity`][mechkit.mechanism_rates.MechanismRates.second_order_velocity]."""

    # ---------------------------------------------------------------- dynamics
    generalized_forces = _AnsweredBy("dynamics", MechanismDynamics.generalized_forces)
    """[`MechanismDynamics.generalized_forces`][mechkit.mechanism_dynamics.MechanismDynamics.generalized_forces]."""
    passive_forces = _AnsweredBy("dynamics", MechanismDynamics.passive_forces)
    """[`MechanismDynamics.passive_forces`][mechkit.mechanism_dynamics.MechanismDynamics.passive_forces]."""
    forward_dynamics = _AnsweredBy("dynamics", MechanismDynamics.forward_dynamics)
    """[`MechanismDynamics.forward_dynamics`][mechkit.mechanism_dynamics.MechanismDynamics.forward_dynamics]."""
    forward_dynamics_batch = _AnsweredBy("dynamics", MechanismDynamics.forward_dynamics_batch)
    """[`MechanismDynamics.forward_dynamics_batch`][mechkit.mechanism_dynamics.MechanismDynamics.forward_dynamics_batch]."""
    inverse_dynamics = _AnsweredBy("dynamics", MechanismDynamics.inverse_dynamics)
    """[`MechanismDynamics.inverse_dynamics`][mechkit.mechanism_dynamics.MechanismDynamics.inverse_dynamics]."""
    inverse_dynamics_batch = _AnsweredBy("dynamics", MechanismDynamics.inverse_dynamics_batch)
    """[`MechanismDynamics.inverse_dynamics_batch`][mechkit.mechanism_dynamics.MechanismDynamics.inverse_dynamics_batch]."""

    # ---------------------------------------------------------------- in time
    def simulate(self, duration: float, **options: Any) -> Any:
        """The mechanism moving under its forces, drives and events.

        Args:
            duration: simulated time (s).
            **options: those of `mechkit.simulation.simulate` (inputs, torques, forces, dt, ...).

        Returns:
            The motion, energies and closure residual (`mechkit.simulation.SimulationResult`).
        """
        from mechkit.simulation import simulate

        return simulate(self, duration, **options)

    def equilibrium(self, held: Mapping[str, float] | None = None, **options: Any) -> Any:
        """The static equilibrium where gravity, the springs and the held inputs balance.

        Args:
            held: joint name -> value (rad or m) of the inputs held still (default: none).
            **options: those of `mechkit.simulation.equilibrium` (elements, q0, tol, max_iter).

        Returns:
            The pose, its residual and its stability (`mechkit.simulation.Equilibrium`).
        """
        from mechkit.simulation import equilibrium

        return equilibrium(self, held, **options)
