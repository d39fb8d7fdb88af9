"""The numerical core: a Pinocchio tree of any joints with loop closures and couplings, and one function
per quantity over it.

The model is built once and never changes (`ClosureModel`: the tree, its closures and couplings, the
rows kept, the actuation); a data is scratch (`ClosureModel.create_data`). Every function takes both,
one sample or, when its name ends in `_batch`, a leading sample axis N:

| quantity | one sample | N samples |
|---|---|---|
| closure residual, Jacobian, drift | `closure_residual`, `closure_jacobian`, `closure_drift` | |
| assembly (loops closed from given values) | `assemble`, `continue_from`, `wrap_into_limits`, `seek_inside_limits` | |
| velocities, J v = 0 | `velocities` | `velocities_batch` |
| accelerations, J a + gamma = 0 | `accelerations` | `accelerations_batch` |
| mobility, singularity | `mobility`, `passive_condition`, `second_order_inconsistency` | |
| forward dynamics | `forward_dynamics` | `forward_dynamics_batch` |
| inverse dynamics, every joint's reaction | `inverse_dynamics` | `inverse_dynamics_batch` |
| what multipliers alone transmit through the joints | `multiplier_reactions` | |
| the tree joints' RNEA wrenches in world axes | `tree_wrenches` (any leading axes) | |

Inside: `records` (closures, couplings, springs, actuators), `joints` (values of any joint type),
`cuts` (rows each closure keeps), `coupling_rows` (a coupling's row on joint values), `tree_paths` (the
columns moving a joint, the cuts in its subtree), `kernel` (the closure-row mathematics), `rank` (the rank
judge), `assembly` (closing loops, from near or far), `inside_limits` (an assembly re-sought inside the
joints' limits), `structure` (loops, Kutzbach count, idle freedoms),
`model`, `kinematics`, `passive_solve` (the free coordinates from the given ones), `inverse` (and `inverse_plan`,
what one sample builds once), `efforts`
(its statics solve), `determinacy`, `forward`, `null_space` (the solutions of J a + gamma = 0),
`pin_constraints` (the one module that speaks Pinocchio's constraint API), `results`. Nothing outside
this package imports those submodules: this face is the contract.
"""

from mechkit.core.assembly import ASSEMBLY_METHODS, Assembly, assemble
from mechkit.core.continuation import continue_from, refuse_outside, wrap_into_limits
from mechkit.core.cuts import CutRows
from mechkit.core.forward import DEFAULTS as FORWARD_DEFAULTS
from mechkit.core.forward import METHODS as FORWARD_METHODS
from mechkit.core.forward import forward_dynamics, forward_dynamics_batch, pinocchio_methods_apply
from mechkit.core.inside_limits import seek_inside_limits
from mechkit.core.inverse import (
    DISTRIBUTIONS,
    inverse_dynamics,
    inverse_dynamics_batch,
    multiplier_reactions,
    tree_wrenches,
)
from mechkit.core.joints import set_value as set_joint_value
from mechkit.core.joints import size as joint_size
from mechkit.core.joints import value as joint_value
from mechkit.core.joints import values as joint_values
from mechkit.core.kernel import ClosureKernel
from mechkit.core.kinematics import (
    accelerations,
    accelerations_batch,
    closure_drift,
    closure_jacobian,
    closure_residual,
    kinematic_pass,
    mobility,
    passive_condition,
    second_order_inconsistency,
    second_order_velocity,
    velocities,
    velocities_batch,
)
from mechkit.core.model import ClosureData, ClosureModel, InputSplit
from mechkit.core.passive_solve import solve_passive
from mechkit.core.pin_constraints import (
    AXIS_ANCHOR_OFFSET,
    LegacyConstraints,
    proximal_settings,
    raw_constraint_dynamics,
)
from mechkit.core.rank import (
    CLOSURE_TOL,
    RANK_TOL,
    independent_rows,
    numerical_rank,
    passive_verdict,
    singular_error,
)
from mechkit.core.records import LOOP_KINDS, ROW_SETS, Actuator, Coupling, JointSpring, LoopClosure, PointToPoint
from mechkit.core.results import (
    BatchInverseDynamicsResult,
    ForwardDynamicsResult,
    InverseDynamicsResult,
    JointReaction,
    Mobility,
)
from mechkit.core.structure import Loop, Structure, analyse, body_name, idle_freedoms, loop_joints

__all__ = [
    "ASSEMBLY_METHODS",
    "AXIS_ANCHOR_OFFSET",
    "CLOSURE_TOL",
    "DISTRIBUTIONS",
    "FORWARD_DEFAULTS",
    "FORWARD_METHODS",
    "LOOP_KINDS",
    "RANK_TOL",
    "ROW_SETS",
    "Actuator",
    "Assembly",
    "BatchInverseDynamicsResult",
    "ClosureData",
    "ClosureKernel",
    "ClosureModel",
    "Coupling",
    "CutRows",
    "ForwardDynamicsResult",
    "InputSplit",
    "InverseDynamicsResult",
    "JointReaction",
    "JointSpring",
    "LegacyConstraints",
    "Loop",
    "LoopClosure",
    "Mobility",
    "PointToPoint",
    "Structure",
    "accelerations",
    "accelerations_batch",
    "analyse",
    "assemble",
    "body_name",
    "closure_drift",
    "closure_jacobian",
    "closure_residual",
    "continue_from",
    "forward_dynamics",
    "forward_dynamics_batch",
    "idle_freedoms",
    "independent_rows",
    "inverse_dynamics",
    "inverse_dynamics_batch",
    "joint_size",
    "joint_value",
    "joint_values",
    "kinematic_pass",
    "loop_joints",
    "mobility",
    "multiplier_reactions",
    "numerical_rank",
    "passive_condition",
    "passive_verdict",
    "pinocchio_methods_apply",
    "proximal_settings",
    "raw_constraint_dynamics",
    "refuse_outside",
    "second_order_inconsistency",
    "second_order_velocity",
    "seek_inside_limits",
    "set_joint_value",
    "singular_error",
    "solve_passive",
    "tree_wrenches",
    "velocities",
    "velocities_batch",
    "wrap_into_limits",
]
