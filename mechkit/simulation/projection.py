"""Projection onto the constraint manifold after each accepted step: closures and driven joints.

Positions: the driven joints are set to their law's values (held joints to theirs) and the core's
closure solve (`mechkit.core.assemble`, minimum-norm Gauss-Newton over the other coordinates) closes
every loop to `POSITION_TOL`. Velocities: the driven joints' rates are set to the law's, and the other
coordinates get the minimum-norm correction dv_F = -J_F^+ (J v) that makes J v = 0 (J the closure
Jacobian, F the undriven columns). Both are the smallest changes, in the coordinates, that put the
state back on the manifold; what they change in the energy is part of the integrator's error, which
the energy balance shows.
"""

from __future__ import annotations

import numpy as np

from mechkit import core
from mechkit.simulation.prescribed import Drives

#: Closure residual (m for position rows) the position projection reaches (ours: below the 1e-10 m the
#: simulation promises, above round-off for metre-sized mechanisms).
POSITION_TOL = 1e-12


class Projection:
    """Projects states of one mechanism onto its closures and its drives.

    Args:
        mech (Mechanism): the mechanism (`mechkit.Mechanism`).
        tol: closure residual to reach (m).
    """

    def __init__(self, mech, tol: float = POSITION_TOL):
        self.mech, self.tol = mech, tol
        self.cm = mech.closure_model
        self.cd = self.cm.create_data()
        self.model = self.cm.model

    def positions(self, q: np.ndarray, drives: Drives, t: float) -> np.ndarray:
        """A configuration with the driven joints on their law and every loop closed.

        Args:
            q: (nq,) the configuration to project.
            drives: the driven joints.
            t: the time (s) their law is taken at.

        Returns:
            (nq,) the projected configuration.

        Raises:
            ClosureNotConverged: the loops do not close near q.
        """
        q = np.array(q, dtype=float)
        values, _, _ = drives.at(t)
        for joint, value in zip(drives.all, values):
            core.set_joint_value(self.model, q, self.mech.joint_id(joint), float(value))
        split = self.cm.split(drives.all)
        return core.assemble(self.cm, self.cd, q, split, tol=self.tol, jacobian_at_trials=False).q

    def velocities(self, q: np.ndarray, v: np.ndarray, drives: Drives, t: float) -> np.ndarray:
        """Velocities with the driven joints' rates on their law and J v = 0.

        Args:
            q: (nq,) an assembled configuration.
            v: (nv,) the velocities to project.
            drives: the driven joints.
            t: the time (s) their law is taken at.

        Returns:
            (nv,) the projected velocities (the undriven ones changed by the least-norm correction).
        """
        v = np.array(v, dtype=float)
        split = self.cm.split(drives.all)
        _, rates, _ = drives.at(t)
        v[split.input_v] = rates
        J = core.closure_jacobian(self.cm, self.cd, q)
        if J.shape[0]:
            free = split.free_v
            v[free] -= np.linalg.lstsq(J[:, free], J @ v, rcond=None)[0]
        return v

    def residual(self, q: np.ndarray) -> float:
        """The largest closure residual at a configuration.

        Args:
            q: (nq,) configuration.

        Returns:
            max |residual| (m for position rows).
        """
        e = core.closure_residual(self.cm, self.cd, q)
        return float(np.max(np.abs(e), initial=0.0))
