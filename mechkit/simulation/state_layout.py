"""The integrated vector y of a simulation and the mechanism's state it stands for.

y = [position part, v (nv), W (n_work)]: W the works integrated beside the motion (the drives', each
force element's non-conservative work), so that the energy balance is integrated by the same method
and tolerances as the motion. The position part is q itself where every joint is a vector space
(revolute, prismatic: dq/dt = v); otherwise (ball, free-flyer, continuous joints) it is a tangent
offset d from a base configuration q_b, q = integrate(q_b, d), d' = dIntegrate_d(q_b, d)^-1 v, and the
base moves to the projected q at every restart of the integrator.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

#: Pinocchio joints whose configuration is a vector space with dq/dt = v.
EUCLIDEAN = (
    "JointModelRX",
    "JointModelRY",
    "JointModelRZ",
    "JointModelRevoluteUnaligned",
    "JointModelPX",
    "JointModelPY",
    "JointModelPZ",
    "JointModelPrismaticUnaligned",
    "JointModelTranslation",
    "JointModelHX",
    "JointModelHY",
    "JointModelHZ",
    "JointModelHelicalUnaligned",
)


class StateLayout:
    """Packs and unpacks y for one model.

    Args:
        model: the tree.
        n_work: how many works ride along.
    """

    def __init__(self, model: pin.Model, n_work: int):
        self.model, self.n_work = model, n_work
        self.euclidean = all(model.joints[j].shortname() in EUCLIDEAN for j in range(1, model.njoints))
        self.npos = model.nq if self.euclidean else model.nv
        self.base = pin.neutral(model)

    def pack(self, q: np.ndarray, v: np.ndarray, works: np.ndarray) -> np.ndarray:
        """The integrated vector of a state (off a vector space, q becomes the base: its offset is 0).

        Args:
            q: (nq,) configuration.
            v: (nv,) velocities.
            works: (n_work,) the works (J).

        Returns:
            y.
        """
        if self.euclidean:
            return np.concatenate([q, v, works])
        self.base = np.array(q, dtype=float)
        return np.concatenate([np.zeros(self.model.nv), v, works])

    def q(self, y: np.ndarray) -> np.ndarray:
        """The configuration of y.

        Args:
            y: the integrated vector.

        Returns:
            (nq,) the configuration (a copy).
        """
        return y[: self.npos].copy() if self.euclidean else pin.integrate(self.model, self.base, y[: self.npos])

    def v(self, y: np.ndarray) -> np.ndarray:
        """The velocities of y.

        Args:
            y: the integrated vector.

        Returns:
            (nv,) the velocities (a view into y).
        """
        return y[self.npos : self.npos + self.model.nv]

    def works(self, y: np.ndarray) -> np.ndarray:
        """The works of y.

        Args:
            y: the integrated vector.

        Returns:
            (n_work,) the works (J; a view into y).
        """
        return y[self.npos + self.model.nv :]

    def derivative(self, y: np.ndarray, a: np.ndarray, powers: np.ndarray) -> np.ndarray:
        """dy/dt at y.

        Args:
            y: the integrated vector.
            a: (nv,) the accelerations.
            powers: (n_work,) the powers (W).

        Returns:
            dy/dt.
        """
        v = self.v(y)
        if self.euclidean:
            dpos = v
        else:
            dpos = np.linalg.solve(pin.dIntegrate(self.model, self.base, y[: self.npos], pin.ARG1), v)
        return np.concatenate([dpos, a, powers])
