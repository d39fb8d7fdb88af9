"""Ten-bar deployment dynamics: prescribed motors, free passive DOF, the simulator's integrator.

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

The Pinocchio route is the simulator itself (`mechkit.simulation`: its equations of motion with the
motor laws as drives, `Mechanism.simulate` for a deployment); the Lagrange routes are integrated by
the simulator's stepping (`mechkit.simulation.run`: the same scipy method and step, projection after
each step). `integrate` runs either at a fixed step on (q, v, W), W the work of motors minus damper,
projecting onto the closures and motor laws after each step or, when projection is off, leaving the
state to drift (optionally with Baumgarte terms in the accelerations).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

import numpy as np

from mechkit import simulation as sim
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
    """Deployment dynamics through the core: the simulator's equations of motion (`MechanismSystem`, the
    constrained ABA of the core) with the motor laws as computed-torque drives and the R5 spring-damper
    the mechanism's own joint spring.

    Args:
        mechanism: `mechkit.load("ten_bar", ...)`.
        baumgarte: (Kp 1/s^2, Kd 1/s) closure stabilisation in the accelerations, or None.
        method: forward-dynamics method of the core ("proximal" = pin.constraintDynamics, or "kkt").
    """

    def __init__(
        self, mechanism: Mechanism, baumgarte: tuple[float, float] | None = None, method: str = "proximal"
    ) -> None:
        self.m, self.baumgarte, self.method = mechanism, baumgarte, method
        self.p = mechanism.params
        self.drives = sim.Drives(MOTORS, self.law)
        self.system = sim.MechanismSystem(mechanism, [mechanism.springs], self.drives, method, baumgarte)
        self.projection = sim.Projection(mechanism)
        self.motor_v = np.array([mechanism.v_index(j) for j in MOTORS])
        self.spring_v = mechanism.v_index(spring_from_urdf(mechanism.urdf).pin)
        self.order = np.array([mechanism.q_index(j) for j in JOINT_ORDER])

    def law(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The motor laws at t.

        Args:
            t: time, s.

        Returns:
            (angles rad, rates rad/s, accelerations rad/s^2) of (R1, R3).
        """
        return motor_law(self.p, t)

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

    def rhs(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        """(accelerations, motor torques (R1, R3) N m, net external power W) at time t (s).

        Args:
            t: time, s.
            q: configuration (nq,).
            v: velocity (nv,).

        Returns:
            (accelerations, motor torques (R1, R3) N m, net external power W).
        """
        ev = self.system.evaluate(t, q, v)
        return ev.a, ev.efforts, float(ev.efforts @ v[self.motor_v]) + float(ev.powers[0])

    def project(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(q, v) on the closures and the motor laws at time t (s).

        Args:
            t: time, s.
            q: configuration (nq,).
            v: velocity (nv,).

        Returns:
            (q, v) on the constraints and the motor laws at t.
        """
        q = self.projection.positions(q, self.drives, t)
        return q, self.projection.velocities(q, v, self.drives, t)

    def residual(self, t: float, q: np.ndarray) -> float:
        """Largest closure residual (m) at q.

        Args:
            t: time, s.
            q: configuration (nq,).

        Returns:
            The residual, m.
        """
        return self.projection.residual(q)

    def energy(self, q: np.ndarray, v: np.ndarray) -> float:
        """Kinetic + gravity + spring energy (J).

        Args:
            q: configuration (nq,).
            v: velocity (nv,).

        Returns:
            The energy, J.
        """
        return self.system.kinetic(q, v) + float(np.sum(self.system.potentials(q)))

    def joint_angles(self, q: np.ndarray) -> np.ndarray:
        """The 9 tree-joint angles in `JOINT_ORDER` (rad).

        Args:
            q: configuration (nq,).

        Returns:
            (9,) angles, rad.
        """
        return q[self.order]


def project(
    rows: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    q: np.ndarray,
    v: np.ndarray,
    motor_rates: np.ndarray,
    what: str,
    tol: float = 1e-13,
    max_iter: int = 20,
) -> tuple[np.ndarray, np.ndarray]:
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
    sample's state), closure residual (m), energy E (J) and net external work W (J).

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
    """Fixed steps of (q, v, W) from t0 to t_end by the simulator's integrator (`mechkit.simulation.run`:
    its default scipy method, error control off), projecting after each step when `project`.

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
    n = len(q0)

    def fun(t: float, y: np.ndarray) -> np.ndarray:
        a, _, power = system.rhs(t, y[:n], y[n : 2 * n])
        return np.concatenate([y[n : 2 * n], a, [power]])

    def onto(t: float, y: np.ndarray) -> np.ndarray:
        return np.concatenate([*system.project(t, y[:n], y[n : 2 * n]), y[2 * n :]])

    times, states = sim.run(
        fun, t0, np.concatenate([q0, v0, [0.0]]), t_end, sim.Options(dt=dt), onto if project else None
    )
    rows = {k: [] for k in ("t", "q", "v", "angles", "torques", "residual", "energy", "work")}
    for t, y in zip(times, states):
        q, v = y[:n], y[n : 2 * n]
        for key, value in (
            ("t", t),
            ("q", q),
            ("v", v),
            ("angles", system.joint_angles(q)),
            ("torques", system.rhs(t, q, v)[1]),
            ("residual", system.residual(t, q)),
            ("energy", system.energy(q, v)),
            ("work", y[2 * n]),
        ):
            rows[key].append(value)
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
