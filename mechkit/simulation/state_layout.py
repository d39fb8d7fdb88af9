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
EUCLIDEAN = ("JointModelRX", "JointModelRY", "JointModelRZ", "JointModelRevoluteUnaligned", "JointModelPX",
             "JointModelPY", "JointModelPZ", "JointModelPrismaticUnaligned", "JointModelTranslation",
             "JointModelHX", "JointModelHY", "JointModelHZ", "JointModelHelicalUnaligned")


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
        """y of a state (and, off a vector space, q becomes the base: its offset is 0)."""
        if self.euclidean:
            return np.concatenate([q, v, works])
        self.base = np.array(q, dtype=float)
        return np.concatenate([np.zeros(self.model.nv), v, works])

    def q(self, y: np.ndarray) -> np.ndarray:
        """The configuration (nq,) of y."""
        return y[:self.npos].copy() if self.euclidean else pin.integrate(self.model, self.base, y[:self.npos])

    def v(self, y: np.ndarray) -> np.ndarray:
        """The velocities (nv,) of y."""
        return y[self.npos:self.npos + self.model.nv]

    def works(self, y: np.ndarray) -> np.ndarray:
        """The works (n_work,) of y (J)."""
        return y[self.npos + self.model.nv:]

    def derivative(self, y: np.ndarray, a: np.ndarray, powers: np.ndarray) -> np.ndarray:
        """dy/dt from the accelerations (nv,) and the powers (n_work,) (W)."""
        v = self.v(y)
        if self.euclidean:
            dpos = v
        else:
            dpos = np.linalg.solve(pin.dIntegrate(self.model, self.base, y[:self.npos], pin.ARG1), v)
        return np.concatenate([dpos, a, powers])
