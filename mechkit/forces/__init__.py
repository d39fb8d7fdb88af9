"""Force elements: named objects giving the generalised forces and body wrenches a mechanism feels.

Each element (`element.ForceElement`) gives, at a state, a `Load` (generalised forces at the joints,
body wrenches) and its part of the energy balance (a potential, or a dissipated or supplied power):

| element | module | role |
|---|---|---|
| `JointSprings`: springs and dampers (loop-cut joints' given the cuts) | `springs` | conservative + dissipative |
| `CoulombFriction`: constant joint friction | `coulomb` | dissipative |
| `ReactionFriction`: friction torque from each revolute joint's reaction | `reaction_friction` | dissipative |
| `TorqueMotor`: a commanded effort within a torque-speed envelope | `motors` | source |
| `Gravity`: another gravity than the model's | `gravity` | conservative |
| `BodyWrench`: a force through a body point and a moment, functions of time | `wrenches` | source |
| `PointToPointForce`: spring, damper, force between two body points | `point_to_point` | any |
| `BushingForce`: Drake's LinearBushingRollPitchYaw between two frames | `bushing` | conservative + dissipative |
| `CutJointSprings`, `CutJointFriction`, `CutJointEffort`: on loop-cut joints | `cut_joints` | all three |

A description declares springs and dampers as URDF `<mechkit:spring>` and `<dynamics damping>`, MJCF stiffness,
springref and damping; constant friction as URDF `<dynamics friction>` and MJCF frictionloss. `ReactionFriction` acts at
tree and cut joints alike (Adams-like).

`described.read` collects what a file says beyond the readers' springs (dampers, friction, joint
limits, motor envelopes). `Mechanism` applies its own `JointSprings` in both dynamics; the simulator
(`mechkit.simulation`) applies any list of elements.
"""

from mechkit.forces.bushing import BushingForce, bushing_forces
from mechkit.forces.coulomb import SPEED_THRESHOLD, CoulombFriction, smooth_sign
from mechkit.forces.cut_joints import CutJointEffort, CutJointFriction, CutJointSprings
from mechkit.forces.described import Described
from mechkit.forces.described import read as read_described
from mechkit.forces.element import (
    ROLES,
    ForceElement,
    ForceState,
    Load,
    generalized_of_wrenches,
    wrench_on_body,
)
from mechkit.forces.gravity import Gravity
from mechkit.forces.motors import TorqueMotor, envelope
from mechkit.forces.point_to_point import PointToPoint, PointToPointForce, point_to_point
from mechkit.forces.reaction_friction import FrictionLocks, PinFriction, ReactionFriction
from mechkit.forces.springs import JointSprings
from mechkit.forces.wrenches import BodyWrench

__all__ = [
    "ROLES",
    "SPEED_THRESHOLD",
    "BodyWrench",
    "BushingForce",
    "CoulombFriction",
    "CutJointEffort",
    "CutJointFriction",
    "CutJointSprings",
    "Described",
    "ForceElement",
    "ForceState",
    "FrictionLocks",
    "Gravity",
    "JointSprings",
    "Load",
    "PinFriction",
    "PointToPoint",
    "PointToPointForce",
    "ReactionFriction",
    "TorqueMotor",
    "bushing_forces",
    "envelope",
    "generalized_of_wrenches",
    "point_to_point",
    "read_described",
    "smooth_sign",
    "wrench_on_body",
]
