"""The whole system's momentum along a motion: what a floating base with no external force conserves.

Linear momentum p = M c' and angular momentum about the world origin h_O = h_G + c x p, from Pinocchio's
centroidal momentum (`pin.computeCentroidalMomentum`: h_G about the centre of mass c); with no gravity
and no external force both stay at their first values, and the centre of mass moves at p / M (stays
still when the system starts at rest). Joint motors and the closures' forces are internal.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit.base import arguments
from mechkit.base.exceptions import InvalidArgument
from mechkit.mechanism import Mechanism


@dataclass(frozen=True)
class MomentumHistory:
    """The momentum of the whole system along a motion.

    Attributes:
        t: (N,) times (s).
        linear: (N, 3) p (kg m/s, world axes).
        angular: (N, 3) h_O, about the world origin (kg m^2/s, world axes).
        com: (N, 3) the centre of mass (m, world).
        mass: the total mass (kg).
        scale: the largest sum over bodies of m |v_body centre| (kg m/s) along the motion: how much
            momentum the bodies carry, against which a drift is judged.
    """

    t: np.ndarray
    linear: np.ndarray
    angular: np.ndarray
    com: np.ndarray
    mass: float
    scale: float

    def drift(self) -> dict[str, float]:
        """How far the momentum and the centre of mass leave their first values' course.

        Returns:
            "linear" (kg m/s) and "angular" (kg m^2/s): the largest change from the first sample;
            "com" (m): the largest distance of the centre of mass from c0 + p0 / M (t - t0);
            "relative_linear": "linear" over `scale`.
        """
        course = self.com[0] + np.outer(self.t - self.t[0], self.linear[0] / self.mass)
        linear = float(np.abs(self.linear - self.linear[0]).max())
        return {
            "linear": linear,
            "angular": float(np.abs(self.angular - self.angular[0]).max()),
            "com": float(np.linalg.norm(self.com - course, axis=1).max()),
            "relative_linear": linear / self.scale if self.scale > 0 else 0.0,
        }


def momentum(mech: Mechanism, t: np.ndarray, q: np.ndarray, v: np.ndarray) -> MomentumHistory:
    """The whole system's momentum at each sample of a motion.

    Args:
        mech: the mechanism (any base; on a fixed one the ground's reactions change the momentum).
        t: (N,) times (s).
        q: (N, nq) configurations.
        v: (N, nv) joint velocities.

    Returns:
        The `MomentumHistory`.

    Raises:
        InvalidArgument: arrays of other shapes (one time and one velocity per configuration) or not finite.
    """
    q = arguments.array("q", q, mech.model.nq, batch=True).reshape(-1, mech.model.nq)
    v = arguments.array("v", v, mech.model.nv, batch=True).reshape(-1, mech.model.nv)
    t = arguments.array("t", t, len(q), batch=False)
    if len(v) != len(q):
        raise InvalidArgument("v", v.shape, f"expected one row per configuration ({len(q)})")
    model, data = mech.model, mech.model.createData()
    linear, angular, com = (np.empty((len(q), 3)) for _ in range(3))
    scale = 0.0
    for k, (qk, vk) in enumerate(zip(q, v)):
        h = pin.computeCentroidalMomentum(model, data, qk, vk)
        com[k], linear[k] = data.com[0], h.linear
        angular[k] = h.angular + np.cross(data.com[0], h.linear)
        pin.forwardKinematics(model, data, qk, vk)
        bodies = sum(
            model.inertias[j].mass
            * np.linalg.norm(data.v[j].linear + np.cross(data.v[j].angular, model.inertias[j].lever))
            for j in range(1, model.njoints)
        )
        scale = max(scale, float(bodies))
    return MomentumHistory(t, linear, angular, com, float(data.mass[0]), scale)
