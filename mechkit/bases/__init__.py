"""A base for every mechanism: fixed, moving (a prescribed carrier motion) or floating (a free bus).

`with_base` puts a mechanism's ground body on root joints of its own (`carrier`); a moving base's
motion is a `BaseMotion` (`base_motion`), joined to the mechanism's input law by `carried`; a floating
system's momentum along a motion: `momentum`; the inputs holding a body's pose in the world:
`hold_pose`, along a base motion with its study: `held_motion`; drives as position servos (`servo`)
and the isolation a held body gets from them on a tilting carrier (`isolation`); a latch's
impulses: `latch_up`.
"""

from mechkit.bases.base_motion import POSE_COLUMNS, BaseMotion, carried, from_callable, from_csv, from_samples
from mechkit.bases.carrier import (
    BASE_JOINTS,
    BASES,
    CARRIER_FRAME,
    CARRIER_JOINT,
    FLOATING_JOINT,
    base_inertia_of,
    base_of,
    with_base,
)
from mechkit.bases.held_motion import HeldMotion, held_motion
from mechkit.bases.holding import Holding, hold_pose
from mechkit.bases.latch_up import LatchUp, latch_up
from mechkit.bases.momentum import MomentumHistory, momentum

__all__ = [
    "BASES",
    "BASE_JOINTS",
    "CARRIER_FRAME",
    "CARRIER_JOINT",
    "FLOATING_JOINT",
    "POSE_COLUMNS",
    "BaseMotion",
    "HeldMotion",
    "Holding",
    "LatchUp",
    "MomentumHistory",
    "base_inertia_of",
    "base_of",
    "carried",
    "from_callable",
    "from_csv",
    "from_samples",
    "held_motion",
    "hold_pose",
    "latch_up",
    "momentum",
    "with_base",
]
