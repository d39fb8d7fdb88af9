"""Ten-bar deployment dynamics: prescribed motors, free passive DOF, RK4 with constraint stabilisation.

Motors R1 and R3 are ideal servos on the cycloidal laws of `params.motor_law`; the passive DOF
(R5) moves under the spring-damper, gravity and the linkage's inertia. Two independent models of
the same motion (`DeploymentSystem`s) share one integrator:

- `PinocchioDeployment` (here): Pinocchio's constrained ABA (`Mechanism.forward_dynamics`,
  `pin.constraintDynamics`) in joint coordinates. It is affine in the joint torques, so three
  calls give the accelerations and the two motor torques that realise the prescribed motor
  accelerations.
- `LagrangeDeployment`, `LagrangeJointDeployment` (`mechkit.mechanisms.ten_bar.lagrange_deployment`):
  the patent's Lagrange equations of the first kind (`mechkit.validation.lagrange`), A f = P with
  the motor torques among the unknowns.

`integrate` is a fixed-step RK4 on (q, v, W) (W the work of motors minus damper); after each step
the state is projected back onto the constraint manifold (closures and motor laws), or, when
projection is off, left to drift (optionally with Baumgarte terms in the accelerations).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import ClosureNotConverged
from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar.lagrange_model import (
    lagrange_from_joints,
)
from mechkit.mechanisms.ten_bar.params import MOTORS, TenBarParams, motor_law, spring_from_urdf

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism


class DeploymentSystem(Protocol):
    """What `integrate` needs from a model of the deployment (`p`: the parameters)."""

    p: TenBarParams

    def rhs(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        """(accelerations, motor torques (R1, R3) N m, net external power W).

        Args:
            t: time, s.
            q: the system's coordinates.
            v: their rates.

        Returns:
            (accelerations, motor torques (R1, R3) N m, net external power W).
        """

    def project(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(q, v) on the constraint manifold at t.

        Args:
            t: time, s.
            q: the system's coordinates.
            v: their rates.

        Returns:
            (q, v) on the constraints and the motor laws at t.
        """

    def residual(self, t: float, q: np.ndarray) -> float:
        """Largest closure residual (m).

        Args:
            t: time, s.
            q: the system's coordinates.

        Returns:
            The residual, m.
        """

    def energy(self, q: np.ndarray, v: np.ndarray) -> float:
        """Kinetic + gravity + spring energy (J).

        Args:
            q: the system's coordinates.
            v: their rates.

        Returns:
            The energy, J.
        """

    def joint_angles(self, q: np.ndarray) -> np.ndarray:
        """The 9 tree-joint angles in `JOINT_ORDER` (rad).

        Args:
            q: the system's coordinates.

        Returns:
            (9,) angles, rad.
        """


JOINT_ORDER = geo.TREE_JOINTS


class PinocchioDeployment:
    """Deployment dynamics through the core (constrained ABA, closure rows).

    Args:
        mechanism: `mechkit.load("ten_bar", ...)`.
        baumgarte: (Kp 1/s^2, Kd 1/s) closure stabilisation in the accelerations, or None.
        method: forward-dynamics method of the core ("proximal" = pin.constraintDynamics, or "kkt").
    """

    def __init__(self, mechanism: Mechanism, baumgarte: tuple[float, float] | None = None,
                 method: str = "proximal") -> None:
        # (0, 0) rather than None: the core keeps the last Baumgarte gains set on its constraint models
        self.m, self.baumgarte, self.method = mechanism, baumgarte or (0.0, 0.0), method
        self.p = mechanism.params
        self.spring = spring_from_urdf(mechanism.urdf)
        self.motor_v = np.array([mechanism.v_index(j) for j in MOTORS])
        self.spring_v = mechanism.v_index(self.spring.pin)
        self.order = np.array([mechanism.q_index(j) for j in JOINT_ORDER])
        self.data = mechanism.model.createData()

    def spring_torque(self, q: np.ndarray, v: np.ndarray) -> float:
        """The R5 spring-damper torque on l56 (N m): k (free angle - q) - c qdot (the mechanism's own joint
        spring, `Mechanism.passive_forces`, which its dynamics apply).

        Args:
            q: configuration (nq,).
            v: velocity (nv,).

        Returns:
            The torque, N m.
        """
        return float(self.m.passive_forces(q, v)[self.spring_v])

    def _fd(self, q, v, tau):
        return self.m.forward_dynamics(q, v, tau, method=self.method, baumgarte=self.baumgarte).a

    def rhs(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        """(accelerations, motor torques (R1, R3) N m, net external power W) at time t (s).

        Args:
            t: time, s.
            q: configuration (nq,).
            v: their rates.

        Returns:
            (accelerations, motor torques (R1, R3) N m, net external power W).
        """
        _, _, acc = motor_law(self.p, t)
        tau = np.zeros(self.m.model.nv)  # the spring acts through the mechanism's dynamics
        a0 = self._fd(q, v, tau)
        G = np.empty((len(a0), 2))
        for k, iv in enumerate(self.motor_v):
            unit = tau.copy()
            unit[iv] += 1.0
            G[:, k] = self._fd(q, v, unit) - a0
        u = np.linalg.solve(G[self.motor_v], acc - a0[self.motor_v])
        power = float(u @ v[self.motor_v]) - self.spring.damping * v[self.spring_v] ** 2
        return a0 + G @ u, u, power

    def _rows(self, t, q):
        pos, _, _ = motor_law(self.p, t)
        e = np.concatenate([self.m.closure_residual(q), q[self.motor_v] - pos])
        G = np.vstack([self.m.closure_jacobian(q), np.eye(self.m.model.nv)[self.motor_v]])
        return e, G

    def project(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(q, v) on the closures and the motor laws at time t (s).

        Args:
            t: time, s.
            q: configuration (nq,).
            v: their rates.

        Returns:
            (q, v) on the constraints and the motor laws at t.

        Raises:
            ClosureNotConverged: the projection does not converge.
        """
        _, rate, _ = motor_law(self.p, t)
        return project(lambda x: self._rows(t, x), q, v, rate, "ten-bar projection (Pinocchio)")

    def residual(self, t: float, q: np.ndarray) -> float:
        """Largest closure residual (m) at q.

        Args:
            t: time, s.
            q: configuration (nq,).

        Returns:
            The residual, m.
        """
        return float(np.max(np.abs(self.m.closure_residual(q))))

    def energy(self, q: np.ndarray, v: np.ndarray) -> float:
        """Kinetic + gravity + spring energy (J).

        Args:
            q: configuration (nq,).
            v: their rates.

        Returns:
            The energy, J.
        """
        model, data = self.m.model, self.data
        kinetic = pin.computeKineticEnergy(model, data, q, v)
        gravity = pin.computePotentialEnergy(model, data, q)
        s = self.spring
        return float(kinetic + gravity + 0.5 * s.stiffness * (q[self.spring_v] - s.free_angle) ** 2)

    def joint_angles(self, q: np.ndarray) -> np.ndarray:
        """The 9 tree-joint angles in `JOINT_ORDER` (rad).

        Args:
            q: configuration (nq,).

        Returns:
            (9,) angles, rad.
        """
        return q[self.order]


def project(rows: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]], q: np.ndarray, v: np.ndarray, motor_rates: np.ndarray, what: str, tol: float = 1e-13,
            max_iter: int = 20) -> tuple[np.ndarray, np.ndarray]:
    """Minimum-norm Gauss-Newton projection of q onto e(q) = 0, then of v onto G v = (0, motor rates).

    Args:
        rows: q -> (e, G): residuals (closure rows, then the 2 motor-law rows) and their Jacobian.
        q: configuration to project.
        v: rates to project.
        motor_rates: the motor-law rates (rad/s) the motor rows of G v must equal.
        what: names the system in the error.
        tol: residual norm to reach.
        max_iter: Gauss-Newton steps allowed.

    Returns:
        (q, v) projected.

    Raises:
        ClosureNotConverged: the residual does not reach tol.
    """
    q = q.copy()
    for it in range(max_iter):  # at least two steps: land on the manifold, not near it
        e, G = rows(q)
        if it >= 2 and np.linalg.norm(e) <= tol:
            break
        q -= np.linalg.lstsq(G, e, rcond=None)[0]
    else:
        raise ClosureNotConverged(float(np.linalg.norm(e)), tol, max_iter, what)
    err = G @ v - np.concatenate([np.zeros(G.shape[0] - len(motor_rates)), motor_rates])
    return q, v - np.linalg.lstsq(G, err, rcond=None)[0]


@dataclass(frozen=True)
class Trajectory:
    """Samples at every step: time (s), joint angles (rad, `JOINT_ORDER`), motor torques (N m, at the
    step's start state), closure residual (m), energy E (J) and net external work W (J).

    E - W is constant for exact dynamics: `energy_error` is its largest drift.
    """

    t: np.ndarray
    q: np.ndarray
    v: np.ndarray
    angles: np.ndarray
    torques: np.ndarray
    residual: np.ndarray
    energy: np.ndarray
    work: np.ndarray

    @property
    def energy_error(self) -> float:
        """Largest drift (J) of E - W from its initial value."""
        balance = self.energy - self.work
        return float(np.max(np.abs(balance - balance[0])))


def integrate(
    system: DeploymentSystem,
    q0: np.ndarray,
    v0: np.ndarray,
    t_end: float,
    dt: float,
    project: bool = True,
    t0: float = 0.0,
) -> Trajectory:
    """Fixed-step RK4 of (q, v, W) from t0 to t_end, projecting after each step when `project`.

    Args:
        system: the dynamics model.
        q0: initial configuration, on the constraint manifold.
        v0: initial rates, on the constraint manifold.
        t_end: end time (s).
        dt: step (s).
        project: project (q, v) onto the closures and motor laws after every step.
        t0: start time (s).

    Returns:
        The trajectory: times, q, v, joint angles, motor torques, residuals, energy error.
    """
    steps = round((t_end - t0) / dt)
    q, v, w = q0.copy(), v0.copy(), 0.0
    rows = {k: [] for k in ("t", "q", "v", "angles", "torques", "residual", "energy", "work")}

    def record(t, a_u):
        rows["t"].append(t)
        rows["q"].append(q.copy())
        rows["v"].append(v.copy())
        rows["angles"].append(system.joint_angles(q))
        rows["torques"].append(a_u)
        rows["residual"].append(system.residual(t, q))
        rows["energy"].append(system.energy(q, v))
        rows["work"].append(w)

    for n in range(steps):
        t = t0 + n * dt
        a1, u1, p1 = system.rhs(t, q, v)
        record(t, u1)
        q2, v2 = q + dt / 2 * v, v + dt / 2 * a1
        a2, _, p2 = system.rhs(t + dt / 2, q2, v2)
        q3, v3 = q + dt / 2 * v2, v + dt / 2 * a2
        a3, _, p3 = system.rhs(t + dt / 2, q3, v3)
        q4, v4 = q + dt * v3, v + dt * a3
        a4, _, p4 = system.rhs(t + dt, q4, v4)
        q = q + dt / 6 * (v + 2 * v2 + 2 * v3 + v4)
        v = v + dt / 6 * (a1 + 2 * a2 + 2 * a3 + a4)
        w = w + dt / 6 * (p1 + 2 * p2 + 2 * p3 + p4)
        if project:
            q, v = system.project(t + dt, q, v)
    _, u_end, _ = system.rhs(t0 + steps * dt, q, v)
    record(t0 + steps * dt, u_end)
    return Trajectory(**{k: np.array(val) for k, val in rows.items()})


def lagrange_state(
    params: TenBarParams, q_pin: np.ndarray, v_pin: np.ndarray, mechanism: Mechanism
) -> tuple[np.ndarray, np.ndarray]:
    """Reference-point coordinates and rates of a Pinocchio state (numpy forward kinematics).

    Args:
        params: the parameters.
        q_pin: a Pinocchio configuration (nq,).
        v_pin: its velocity (nv,).
        mechanism: the ten-bar (joint indices).

    Returns:
        (q_L, qd_L), 3 per link.
    """
    angles = {j: float(q_pin[mechanism.q_index(j)]) for j in JOINT_ORDER}
    rates = {j: float(v_pin[mechanism.v_index(j)]) for j in JOINT_ORDER}
    return lagrange_from_joints(params, angles, rates)


def deploy(
    system: DeploymentSystem, q0: np.ndarray, dt: float, t_end: float | None = None, project: bool = True
) -> Trajectory:
    """Integrate from rest at q0 (stowed) to t_end (default: the end of the motor laws).

    Args:
        system: the dynamics model.
        q0: the stowed configuration, in the system's coordinates.
        dt: RK4 step, s.
        t_end: end time, s.
        project: project after every step.

    Returns:
        The trajectory.
    """
    end = system.p.deploy_time if t_end is None else t_end
    return integrate(system, q0, np.zeros_like(q0), end, dt, project=project)
