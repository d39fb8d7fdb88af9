"""Simulation in time of any mechanism: constrained dynamics under force elements, drives and events,
with the energy balance as its own check.

`simulate(mech, duration, ...)` (also `Mechanism.simulate`) integrates the core's constrained forward
dynamics (`system`) with a scipy one-step method (`integrator`: adaptive, or a fixed step), projects
onto the closures and drives after every accepted step (`projection`), follows prescribed inputs by
computed-torque motors or applies given torques (`drives`, `mechkit.forces.TorqueMotor`), stops or
bounces joints at their limits and locks latches (`events`), and records every step with its
reactions, energies and works (`recorder`, `result`). `equilibrium` finds where gravity, springs and
held inputs balance and `small_oscillations` the eigenvalues of the motion linearised about it;
`friction` gives inverse dynamics with joint friction from the reactions.
"""

from mechkit.simulation.declared import default_forces, file_limits, torque_motors
from mechkit.simulation.equilibrium import Equilibrium, equilibrium
from mechkit.simulation.events import Impact, Latch, Limit, impact
from mechkit.simulation.friction import FrictionInverse, inverse_dynamics
from mechkit.simulation.integrator import ATOL, METHODS, RTOL, Event, IntegrationFailed, Options, Stepper, run
from mechkit.simulation.prescribed import Drives, law_of_samples, prescribed
from mechkit.simulation.projection import DRIFT_TOL, POSITION_TOL, Projection
from mechkit.simulation.result import SimulationResult, write_csv, write_parquet
from mechkit.simulation.simulate import simulate
from mechkit.simulation.small_oscillations import SmallOscillations, small_oscillations
from mechkit.simulation.system import Evaluation, MechanismSystem

__all__ = [
    "ATOL",
    "DRIFT_TOL",
    "METHODS",
    "POSITION_TOL",
    "RTOL",
    "Drives",
    "Equilibrium",
    "Evaluation",
    "Event",
    "FrictionInverse",
    "Impact",
    "IntegrationFailed",
    "Latch",
    "Limit",
    "MechanismSystem",
    "Options",
    "Projection",
    "SimulationResult",
    "SmallOscillations",
    "Stepper",
    "default_forces",
    "equilibrium",
    "file_limits",
    "impact",
    "inverse_dynamics",
    "law_of_samples",
    "prescribed",
    "run",
    "simulate",
    "small_oscillations",
    "torque_motors",
    "write_csv",
    "write_parquet",
]
