"""Gravity as a force element: another gravity than the model's (a ground test, orbit, the Moon).

Pinocchio applies the model's gravity (`model.gravity`: the description's, MJCF `<option gravity>`,
else -9.81 m/s^2 along z) in every dynamics; `Gravity(g)` makes the bodies feel g instead, by adding
m (g - g_model) at each centre of mass. Its potential, -sum m (g - g_model) . c, joins the model's
own (`pin.computePotentialEnergy`), so the balance sees -sum m g . c.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters
from mechkit.forces.element import ForceElement, ForceState, Load


class Gravity(ForceElement):
    """Uniform gravity g (m/s^2, world frame) in place of the model's.

    Args:
        model: the tree.
        g (ArrayLike): (3,) the gravity vector (m/s^2, world); (0, 0, 0) for weightlessness.
        name: the element's name.

    Raises:
        InvalidParameters: g not three finite numbers.
    """

    role = "conservative"

    def __init__(self, model: pin.Model, g, name: str = "gravity"):
        g = np.asarray(g, dtype=float)
        if g.shape != (3,) or not np.all(np.isfinite(g)):
            raise InvalidParameters("g", g, "gravity needs three finite numbers (m/s^2, world frame)")
        self.name, self.g = name, g
        self.delta = g - model.gravity.linear
        self._masses = np.array([model.inertias[j].mass for j in range(model.njoints)])
        self._coms = np.array([model.inertias[j].lever for j in range(model.njoints)])

    def load(self, state: ForceState) -> Load:
        """m (g - g_model) at every centre of mass, as body wrenches.

        Args:
            state: the state (its world placements are read).

        Returns:
            The `Load`: body wrenches (njoints, 6) in `fext` convention, no generalised forces, power 0.
        """
        out = np.zeros((state.model.njoints, 6))
        for j in np.flatnonzero(self._masses[1:] > 0) + 1:
            f = state.data.oMi[int(j)].rotation.T @ (self._masses[j] * self.delta)  # joint frame
            out[j, :3], out[j, 3:] = f, np.cross(self._coms[j], f)
        return Load(None, out, 0.0)

    def energy(self, model: pin.Model, data: pin.Data, q: np.ndarray) -> float:
        """The potential -sum m (g - g_model) . c, c the centres of mass in the world.

        Args:
            model: the tree's Pinocchio model.
            data: its data after `forwardKinematics(q)`.
            q: (nq,) configuration (unused beyond `data`).

        Returns:
            The potential energy (J) of the gravity difference.
        """
        total = 0.0
        for j in np.flatnonzero(self._masses[1:] > 0) + 1:
            c = data.oMi[int(j)].act(self._coms[j])
            total -= self._masses[j] * float(self.delta @ c)
        return total
