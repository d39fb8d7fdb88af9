"""Events of a simulation: joint limits (stop or bounce) and latches, and the impact they cause.

- `Limit(joint, lower, upper, restitution)`: when the joint reaches a bound moving outwards, an
  impact sets its rate to -restitution times the rate it arrived with. With restitution 0 (a stop),
  or where the rebound would be slower than `REST_RATE`, the joint is then held at the bound (a
  driven joint of zero rate) until the effort holding it would have to pull it off the bound: then
  it is released.
- `Latch(joint, value, direction)`: when the joint reaches `value` (from below for direction +1,
  from above for -1, either for 0), a plastic impact stops it and it stays held there.

The impact (rigid, frictionless, in joint space): the velocity jump that changes the kinetic energy
least, v+ = v- + M^-1 G^T L, under G v+ = c, with G the closure rows, the driven joints (their law's
rates unchanged: a prescribed motor is stiff against impacts too), the held joints (rate 0) and the
impacting joint (its new rate). The kinetic energy changes by
T+ - T- = L_drives . rates + L_joint (r- + r+) / 2 (the closure rows do no work): the first term is
the motors' impulsive work, minus the second the energy the impact dissipates (>= 0 for a
restitution in [0, 1]).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.base.exceptions import InvalidParameters

#: Rebound rate (rad/s or m/s) below which a bouncing joint is held at its bound instead (ours: ends
#: the ever-shorter bounces of a restitution below one in finite time).
REST_RATE = 1e-3


@dataclass(frozen=True)
class Limit:
    """A joint's bounds and what happens there.

    Attributes:
        joint: the joint (one freedom).
        lower: its lower bound (rad or m).
        upper: its upper bound (rad or m).
        restitution: 0 (stop and hold) to 1 (elastic bounce).
    """

    joint: str
    lower: float
    upper: float
    restitution: float = 0.0

    def __post_init__(self) -> None:
        if not self.lower < self.upper or not 0.0 <= self.restitution <= 1.0:
            raise InvalidParameters(
                f"limit of {self.joint}",
                (self.lower, self.upper, self.restitution),
                "needs lower < upper and a restitution in [0, 1]",
            )


@dataclass(frozen=True)
class Latch:
    """A joint that locks when it reaches a value.

    Attributes:
        joint: the joint (one freedom).
        value: where it locks (rad or m).
        direction: +1 reached from below, -1 from above, 0 either way.
    """

    joint: str
    value: float
    direction: int = 0


@dataclass(frozen=True)
class Impact:
    """What an impact did.

    Attributes:
        v: (nv,) velocities after it.
        drive_work: the driven joints' impulsive work (J).
        dissipated: the energy the impacting joint's stop took (J, >= 0 for restitution <= 1).
    """

    v: np.ndarray
    drive_work: float
    dissipated: float


def impact(
    cm: core.ClosureModel,
    cd: core.ClosureData,
    q: np.ndarray,
    v: np.ndarray,
    drive_v: np.ndarray,
    drive_rates: np.ndarray,
    joint_v: int,
    rate: float,
) -> Impact:
    """The velocity jump of least kinetic-energy change that keeps the closures and sets the driven and
    impacting joints' rates (see the module docstring).

    Args:
        cm: the closure model.
        cd: a data of it (scratch).
        q: (nq,) the configuration at the impact.
        v: (nv,) the velocities before it.
        drive_v: (k,) velocity indices of the driven joints.
        drive_rates: (k,) their rates after the impact (rad/s or m/s).
        joint_v: velocity index of the impacting joint.
        rate: its rate after the impact (rad/s or m/s).

    Returns:
        The `Impact`: velocities (nv,) after it, the drives' impulsive work and the energy dissipated (J).
    """
    model = cm.model
    J = core.closure_jacobian(cm, cd, q)
    eye = np.eye(model.nv)
    G = np.vstack([J, eye[drive_v], eye[[joint_v]]])
    c = np.concatenate([np.zeros(J.shape[0]), drive_rates, [rate]])
    M = pin.crba(model, cd.pin, q)
    M = np.triu(M) + np.triu(M, 1).T
    Minv_Gt = np.linalg.solve(M, G.T)
    L = np.linalg.lstsq(G @ Minv_Gt, c - G @ v, rcond=None)[0]
    after = v + Minv_Gt @ L
    k = J.shape[0]
    drive_work = float(L[k : k + len(drive_v)] @ drive_rates)
    dissipated = -float(L[-1] * (v[joint_v] + after[joint_v]) / 2)
    return Impact(after, drive_work, dissipated)
