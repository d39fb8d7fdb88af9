"""The Jacobian of a simulation's first-order system dy/dt = f(t, y), for the implicit Radau IIA.

scipy's Radau estimates the Jacobian by forward differences, one evaluation of the equations of motion
(a constrained forward dynamics under every force element) per component of y, each time its Newton
iteration converges slowly (on the stiff flyball governor: 602 times in 696 steps). This module builds it
from Pinocchio's derivatives instead, for y = [q, v, W] (`StateLayout`, q a vector space):

    d/dt q = v,   d/dt v = a(q, v, tau(q, v)),   d/dt W = powers(q, v),

so dq'/dv = I, da/dq = A_q + A_tau tau_q, da/dv = A_v + A_tau tau_v and the works' rows are the powers'
derivatives (the works do not feed back: their columns are 0). A_v and A_tau are Pinocchio's
`computeConstraintDynamicsDerivatives` after `constraintDynamics` on the legacy constraint models
(`core.LegacyConstraints`, the "proximal" method's); A_q is Pinocchio's too on a tree, but on a loop
closure Pinocchio 4.1's A_q disagrees with central differences of its own `constraintDynamics`
(measured: 0.21 of the largest entry on the four-bar, in the crank's column; the ten-bar's first column
likewise), so there A_q is taken by central differences of the forward dynamics at
fixed tau (2 nv solves, no force element evaluated). The force elements' tau(q, v) (generalised forces
plus J^T of their body wrenches) and powers: the point-to-point springs and dampers without a law
analytically (`strut_derivatives`: the spring along the line, the force turning with the line, the points'
Jacobians changing with q, the damper's rate), every other element by central differences of its own
loads (kinematics only, no dynamics).

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
from mechkit.forces import ForceState, PointToPointForce, generalized_of_wrenches
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

    def loads(self, t: float, q: np.ndarray, v: np.ndarray, which: list[int]) -> tuple[np.ndarray, np.ndarray]:
        """Some force elements' generalised forces, their body wrenches included, and their powers.

        Args:
            t: the time (s).
            q: (nq,) configuration.
            v: (nv,) velocities.
            which: the elements (indices into the system's).

        Returns:
            (nv,) tau (N m or N) and (len(which),) the powers (W).
        """
        if not which:
            return np.zeros(self.model.nv), np.zeros(0)
        state = ForceState.at(self.model, self.data, q, v, t)
        tau, fext, powers = self.system._loads(state, which)
        if fext.any():
            tau = tau + generalized_of_wrenches(self.model, state.data, fext)
        return tau, powers

    def _load_derivatives(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """d tau / d(q, v) (nv, nq + nv) and d powers / d(q, v) (n_elements, nq + nv): the struts' analytic
        (`strut_derivatives`), the other elements' by central differences of their loads."""
        nq, nv, elements = self.model.nq, self.model.nv, self.system.elements
        tau_x, powers_x = np.zeros((nv, nq + nv)), np.zeros((len(elements), nq + nv))
        struts = [k for k, e in enumerate(elements) if isinstance(e, PointToPointForce) and not e.element.law]
        if struts:
            kinematics(self.model, self.data, q, v)
            for k in struts:
                tau_k, powers_x[k] = strut_derivatives(self.model, self.data, elements[k], v)
                tau_x += tau_k
        others = [k for k in range(len(elements)) if k not in struts]
        if not others:
            return tau_x, powers_x
        x = np.concatenate([q, v])
        for i in range(nq + nv):
            h = LOAD_STEP * max(1.0, abs(x[i]))
            columns = []
            for sign in (1.0, -1.0):
                xs = x.copy()
                xs[i] += sign * h
                columns.append(np.concatenate(self.loads(t, xs[:nq], xs[nq:], others)))
            column = (columns[0] - columns[1]) / (2 * h)
            tau_x[:, i] += column[:nv]
            powers_x[others, i] = column[nv:]
        return tau_x, powers_x

    def dynamics(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> tuple[np.ndarray, ...]:
        """The constrained forward dynamics' accelerations and their derivatives.

        Args:
            q: (nq,) configuration.
            v: (nv,) velocities.
            tau: (nv,) joint efforts (N m or N).

        Returns:
            (a (nv,), da/dq (nv, nq), da/dv (nv, nv), da/dtau (nv, nv)).
        """
        a = self.legacy.dynamics(q, v, tau, self.settings)[0]
        d = pin.computeConstraintDynamicsDerivatives(
            self.model, self.legacy.data, self.legacy.models, self.legacy.datas, self.settings
        )
        a_q, a_v, a_tau = (np.array(x, dtype=float).reshape(self.model.nv, -1) for x in d[:3])
        if self.loops:  # Pinocchio 4.1's A_q is wrong on loop closures (module docstring)
            a_q = np.empty((self.model.nv, self.model.nq))
            for k in range(self.model.nq):
                h, qs = DYNAMICS_STEP * max(1.0, abs(q[k])), q.copy()
                qs[k] += h
                ahead = self.legacy.dynamics(qs, v, tau, self.settings)[0]
                qs[k] -= 2 * h
                a_q[:, k] = (ahead - self.legacy.dynamics(qs, v, tau, self.settings)[0]) / (2 * h)
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
        tau, _ = self.loads(t, q, v, list(range(len(self.system.elements))))
        tau_x, powers_x = self._load_derivatives(t, q, v)
        _, a_q, a_v, a_tau = self.dynamics(q, v, tau)
        out = np.zeros((y.size, y.size))
        out[:nq, nq : nq + nv] = np.eye(nv)
        out[nq : nq + nv, :nq] = a_q + a_tau @ tau_x[:, :nq]
        out[nq : nq + nv, nq : nq + nv] = a_v + a_tau @ tau_x[:, nq:]
        out[nq + nv + 1 :, : nq + nv] = powers_x  # row nq + nv: the drives' work (no drives here)
        return out


def kinematics(model: pin.Model, data: pin.Data, q: np.ndarray, v: np.ndarray) -> None:
    """What `strut_derivatives` reads: placements, world Jacobians and the velocities' derivatives at (q, v).

    Args:
        model: the tree's Pinocchio model.
        data: its data (overwritten).
        q: (nq,) configuration.
        v: (nv,) velocities.
    """
    pin.computeForwardKinematicsDerivatives(model, data, q, v, np.zeros(model.nv))
    pin.computeJointJacobians(model, data, q)


def _point(model: pin.Model, data: pin.Data, frame: str, local: np.ndarray) -> tuple[np.ndarray, ...]:
    """A body point's position x (3,), its Jacobian J_p (3, nv), the derivative of its velocity in q (3, nv),
    and H (nv, nv, 3): d J_p[:, k] / d q_i at [i, k] (world axes; the ground: zeros)."""
    f = model.frames[model.getFrameId(frame)]
    joint, r = int(f.parentJoint), f.placement.act(np.asarray(local, dtype=float))
    nv = model.nv
    if joint == 0:
        return r, np.zeros((3, nv)), np.zeros((3, nv)), np.zeros((nv, nv, 3))
    x = data.oMi[joint].act(r)
    Jw = pin.getJointJacobian(model, data, joint, pin.WORLD)  # twists about the world origin
    lin, ang = Jw[:3], Jw[3:]
    J = lin + np.cross(ang.T, x).T
    dv_dq = pin.getPointVelocityDerivatives(model, data, joint, pin.SE3(np.eye(3), r), pin.LOCAL_WORLD_ALIGNED)[0]
    H = np.cross(ang.T[None, :, :], J.T[:, None, :])  # [i, k]: omega_k x J_p[:, i] (x moves with q_i)
    chain = [model.joints[j].idx_v for j in model.supports[joint][1:]]
    for a, i in enumerate(chain):  # column k moves with q_i for i before k: d Jw_k / d q_i = ad(Jw_i) Jw_k
        for k in chain[a + 1 :]:
            d_lin = np.cross(ang[:, i], lin[:, k]) + np.cross(lin[:, i], ang[:, k])
            H[i, k] += d_lin + np.cross(np.cross(ang[:, i], ang[:, k]), x)
    return x, J, dv_dq, H


def strut_derivatives(
    model: pin.Model, data: pin.Data, strut: PointToPointForce, v: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The derivatives of a point-to-point element's generalised force G^T u F and damper power -c L_dot^2 in
    (q, v), F = -k (L - L0) + F0 - c L_dot (no law), G = J_b - J_a, u the unit vector from a to b.

    Args:
        model: the tree's Pinocchio model (joints with dq/dt = v).
        data: its data after `kinematics(q, v)`.
        strut: the element.
        v: (nv,) the velocities.

    Returns:
        (nv, nq + nv) d tau / d(q, v) and (nq + nv,) d power / d(q, v).
    """
    e = strut.element
    xa, Ja, Da, Ha = _point(model, data, e.frame_a, e.point_a)
    xb, Jb, Db, Hb = _point(model, data, e.frame_b, e.point_b)
    G, d = Jb - Ja, xb - xa
    L = float(np.linalg.norm(d))
    u = d / L
    d_dot = G @ v
    rate = float(u @ d_dot)
    P = (np.eye(3) - np.outer(u, u)) / L
    du_dq = P @ G
    rate_q, rate_v = d_dot @ du_dq + u @ (Db - Da), u @ G
    F = -e.stiffness * (L - e.free_length) + e.force - e.damping * rate
    F_q, F_v = -e.stiffness * (u @ G) - e.damping * rate_q, -e.damping * rate_v
    f = F * u
    tau_q = (Hb - Ha) @ f + G.T @ (du_dq * F + np.outer(u, F_q))
    tau_v = G.T @ np.outer(u, F_v)
    power = -2.0 * e.damping * rate * np.concatenate([rate_q, rate_v])
    return np.hstack([tau_q, tau_v]), power
