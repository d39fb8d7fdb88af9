"""A free-flyer root in the simulator: the forward dynamics it runs by default, and the whole system's
momentum along the run, which a floating system with no gravity and no external force conserves.

Pinocchio's proximal solver ("proximal", the default elsewhere) is not the default on a floating bus: with
the bus's inertia in its Delassus scale its answers are rough (measured on the spherical platform on a
20 kg bus over 0.6 s: 607 steps and the energy balance at 3.5e-5 of the exchange, against 42 steps and
2e-9 with "kkt"), so "kkt" is taken unless a method is asked for, and the result says so.

Momentum: linear p = M c' and angular about the world origin h_O = h_G + c x p, from Pinocchio's centroidal
momentum (`pin.computeCentroidalMomentum`: h_G about the centre of mass c); with no gravity and no
external force both stay at their first values and the centre of mass moves at p / M. Joint motors and
the closures' forces are internal. (`mechkit.bases.momentum` reads it for any mechanism.)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

#: The note of a run whose default dynamics the free-flyer root changed.
FLOATING_NOTE = "kkt (the default on a free-flyer root, where proximal is rough)"


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


def system_momentum(model: pin.Model, t: np.ndarray, q: np.ndarray, v: np.ndarray) -> MomentumHistory:
    """The whole system's momentum at each sample (arrays as given: checked by the callers).

    Args:
        model: the Pinocchio model (any root).
        t: (N,) times (s).
        q: (N, nq) configurations.
        v: (N, nv) joint velocities.

    Returns:
        The `MomentumHistory`.
    """
    data = model.createData()
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
    return MomentumHistory(np.asarray(t, dtype=float), linear, angular, com, float(data.mass[0]), scale)


def free_flyer_root(model: pin.Model) -> bool:
    """Whether the model's first joint is a free-flyer (a floating base).

    Args:
        model: the Pinocchio model.

    Returns:
        True for a free-flyer root joint.
    """
    return model.njoints > 1 and model.joints[1].shortname() == "JointModelFreeFlyer"


def default_dynamics(model: pin.Model, exact: bool) -> tuple[str, str]:
    """The forward-dynamics method of a run that asked for none.

    Args:
        model: the Pinocchio model.
        exact: whether the run needs mechkit's own closure rows (reactions in the forces, cuts Pinocchio
            cannot express).

    Returns:
        (method, note): "kkt" or "proximal", and why where the root changed it ("" otherwise).
    """
    if exact:
        return "kkt", ""
    return ("kkt", FLOATING_NOTE) if free_flyer_root(model) else ("proximal", "")


def run_momentum(model: pin.Model, t: np.ndarray, q: np.ndarray, v: np.ndarray) -> MomentumHistory | None:
    """A run's momentum where its root is a free-flyer.

    Args:
        model: the Pinocchio model.
        t: (N,) times (s).
        q: (N, nq) configurations.
        v: (N, nv) velocities.

    Returns:
        `system_momentum`, or None on another root.
    """
    return system_momentum(model, t, q, v) if free_flyer_root(model) else None
