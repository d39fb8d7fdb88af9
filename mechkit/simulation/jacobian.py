"""The Jacobian of a simulation's first-order system dy/dt = f(t, y), for the implicit Radau IIA.

scipy's Radau estimates the Jacobian by forward differences, one evaluation of the equations of motion
(a constrained forward dynamics under every force element) per component of y, and re-estimates it at
every restart of the integrator (after every step here: the projection restarts it). This module builds
it from Pinocchio's derivatives instead, for y = [q, v, W] (`StateLayout`, q a vector space):

    d/dt q = v,   d/dt v = a(q, v, tau(q, v)),   d/dt W = powers(q, v),

so dq'/dv = I, da/dq = A_q + A_tau tau_q, da/dv = A_v + A_tau tau_v and the works' rows are the powers'
derivatives (the works do not feed back: their columns are 0). A_v and A_tau are Pinocchio's
`computeConstraintDynamicsDerivatives` after `constraintDynamics` on the legacy constraint models
(`core.LegacyConstraints`, the "proximal" method's); A_q is Pinocchio's too on a tree, but on a loop
closure Pinocchio 4.1's A_q disagrees with central differences of its own `constraintDynamics`
(measured: 0.21 of the largest entry on the four-bar, in the columns of the joints that carry a cut's
side but are not its joints), so there A_q is taken by central differences of the forward dynamics at
fixed tau (2 nv solves, no force element evaluated). The force elements' tau(q, v) (generalised forces
plus J^T of their body wrenches) and powers have no derivative of their own: both are taken by central
differences of the elements' loads (kinematics only, no dynamics).

Where these do not hold, `SystemJacobian.current` gives None and scipy's own differences are used:
off a vector space (ball and free joints: y holds a tangent offset), with drives (the computed-torque
efforts), with friction from the reactions, with Baumgarte terms, with a cut or coupling no legacy
model expresses, and in the simulator's near-singular mode (its stages are projected).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.forces import ForceState, generalized_of_wrenches
from mechkit.simulation.state_layout import StateLayout

#: Relative step of the central differences of the force elements' loads (ours: truncation ~h^2,
#: rounding ~1e-16 / h, both near 1e-11 of the load's scale).
LOAD_STEP = 6e-6
#: Relative step of the central differences of the constrained dynamics in q on loops (ours: truncation
#: ~h^2, the proximal solve's own noise (~1e-10 of the accelerations) over h: both near 1e-9 of them).
DYNAMICS_STEP = 1e-5

Jacobian = Callable[[float, np.ndarray], np.ndarray]


class SystemJacobian:
    """The Jacobian of a `MechanismSystem`'s first-order system (see the module docstring).

    Args:
        system (MechanismSystem): the equations of motion.
        layout: the layout of y (positions, velocities, works: the drives' work first, then each element's).
        near: () -> whether the simulator's stages are projected onto the manifold now (its
            near-singular mode), or None: never.
    """

    def __init__(self, system: Any, layout: StateLayout, near: Callable[[], bool] | None = None):
        self.system, self.layout, self.near = system, layout, near
        cm = system.cm
        self.model = cm.model
        self.data = self.model.createData()
        self.usable = (
            layout.euclidean
            and not system.friction
            and system.method in core.FORWARD_METHODS
            and system.settings.get("baumgarte", (0.0, 0.0)) == (0.0, 0.0)
            and core.pinocchio_methods_apply(cm)
        )
        if not self.usable:
            return
        self.legacy = core.LegacyConstraints(self.model, list(cm.kernel.cuts), len(cm.kernel.couplings))
        mu, accuracy, iterations = core.FORWARD_DEFAULTS["proximal"]
        self.settings = core.proximal_settings(
            accuracy / cm.delassus_scale, mu * cm.delassus_scale, iterations
        )  # the "proximal" method's
        self.loops = len(self.legacy.models) > 0

    def current(self) -> Jacobian | None:
        """The Jacobian function for the next steps, or None where scipy's differences must be used.

        Returns:
            (t, y) -> (n, n) matrix, n the size of y; or None (see the module docstring).
        """
        if not self.usable or self.system.drive_v.size or self.system.method not in core.FORWARD_METHODS:
            return None
        if self.near is not None and self.near():
            return None
        return self.__call__

    def loads(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The force elements' generalised forces, their body wrenches included, and their powers.

        Args:
            t: the time (s).
            q: (nq,) configuration.
            v: (nv,) velocities.

        Returns:
            (nv,) tau (N m or N) and (n_elements,) the powers (W).
        """
        system = self.system
        if not system.elements:
            return np.zeros(self.model.nv), np.zeros(0)
        state = ForceState.at(self.model, self.data, q, v, t)
        tau, fext, powers = system._loads(state, system.plain)
        if fext.any():
            tau = tau + generalized_of_wrenches(self.model, state.data, fext)
        return tau, powers

    def _load_derivatives(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Central differences of `loads` in (q, v): (nv + n_el, nq + nv), tau's rows then the powers'."""
        nq, nv = self.model.nq, self.model.nv
        out = np.zeros((nv + len(self.system.elements), nq + nv))
        if not self.system.elements:
            return out[:nv], out[nv:]
        x = np.concatenate([q, v])
        for k in range(nq + nv):
            h = LOAD_STEP * max(1.0, abs(x[k]))
            columns = []
            for sign in (1.0, -1.0):
                xs = x.copy()
                xs[k] += sign * h
                columns.append(np.concatenate(self.loads(t, xs[:nq], xs[nq:])))
            out[:, k] = (columns[0] - columns[1]) / (2 * h)
        return out[:nv], out[nv:]

    def dynamics(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> tuple[np.ndarray, ...]:
        """The constrained forward dynamics' accelerations and their derivatives.

        Args:
            q: (nq,) configuration.
            v: (nv,) velocities.
            tau: (nv,) joint efforts (N m or N).

        Returns:
            (a (nv,), da/dq (nv, nq), da/dv (nv, nv), da/dtau (nv, nv)).
        """
        a = self.legacy.dynamics(q, v, tau, self.settings).copy()
        d = pin.computeConstraintDynamicsDerivatives(
            self.model, self.legacy.data, self.legacy.models, self.legacy.datas, self.settings
        )
        a_q, a_v, a_tau = (np.array(x, dtype=float).reshape(self.model.nv, -1) for x in d[:3])
        if self.loops:  # Pinocchio 4.1's A_q is wrong on loop closures (module docstring)
            a_q = np.empty((self.model.nv, self.model.nq))
            for k in range(self.model.nq):
                h, qs = DYNAMICS_STEP * max(1.0, abs(q[k])), q.copy()
                qs[k] += h
                ahead = self.legacy.dynamics(qs, v, tau, self.settings).copy()
                qs[k] -= 2 * h
                a_q[:, k] = (ahead - self.legacy.dynamics(qs, v, tau, self.settings)) / (2 * h)
        return a, a_q, a_v, a_tau

    def __call__(self, t: float, y: np.ndarray) -> np.ndarray:
        """The Jacobian of dy/dt at y.

        Args:
            t: the time (s).
            y: the integrated vector.

        Returns:
            (n, n) d(dy/dt)/dy.
        """
        layout, nq, nv = self.layout, self.model.nq, self.model.nv
        q, v = layout.q(y), np.array(layout.v(y))
        tau, _ = self.loads(t, q, v)
        tau_x, powers_x = self._load_derivatives(t, q, v)
        _, a_q, a_v, a_tau = self.dynamics(q, v, tau)
        out = np.zeros((y.size, y.size))
        out[:nq, nq : nq + nv] = np.eye(nv)
        out[nq : nq + nv, :nq] = a_q + a_tau @ tau_x[:, :nq]
        out[nq : nq + nv, nq : nq + nv] = a_v + a_tau @ tau_x[:, nq:]
        out[nq + nv + 1 :, : nq + nv] = powers_x  # row nq + nv: the drives' work (no drives here)
        return out
