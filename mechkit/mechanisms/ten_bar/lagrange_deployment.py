"""The ten-bar's deployment by the patent's Lagrange equations of the first kind (numpy only): the
`DeploymentSystem`s of the Lagrange route, in reference-point coordinates (`LagrangeDeployment`) and in
tree-joint coordinates (`LagrangeJointDeployment`), integrated by `dynamics.integrate` like the
Pinocchio route."""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar.dynamics import JOINT_ORDER, project
from mechkit.mechanisms.ten_bar.lagrange_model import (
    TreeKinematics,
    joint_angles_from_lagrange,
    lagrange_linkage,
)
from mechkit.mechanisms.ten_bar.params import MOTORS, TenBarParams, motor_law


class LagrangeDeployment:
    """Deployment dynamics by the patent's Lagrange first-kind method (numpy only)."""

    def __init__(self, params: TenBarParams) -> None:
        self.p = params
        self.L = lagrange_linkage(params)

    def rhs(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        """(reference-point accelerations, motor torques (R1, R3) N m, net external power W) at t (s).

        Args:
            t: time, s.
            q: reference-point coordinates (3 per link).
            v: their rates.

        Returns:
            (accelerations, motor torques (R1, R3) N m, net external power W).
        """
        _, _, acc = motor_law(self.p, t)
        sol = self.L.solve(q, v, acc)
        u = np.array([sol.efforts[m] for m in MOTORS])
        power = self.L.power(q, v, sol.efforts)
        return sol.qdd, u, power["motor"] - power["damper"]

    def project(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(q, v) on the pin constraints and the motor laws at time t (s).

        Args:
            t: time, s.
            q: reference-point coordinates (3 per link).
            v: their rates.

        Returns:
            (q, v) on the constraints and the motor laws at t.

        Raises:
            ClosureNotConverged: the projection does not converge.
        """
        pos, rate, _ = motor_law(self.p, t)
        return self.L.project(q, v, pos, rate)

    def residual(self, t: float, q: np.ndarray) -> float:
        """Largest pin-constraint residual (m) at q.

        Args:
            t: time, s.
            q: reference-point coordinates (3 per link).

        Returns:
            The residual, m.
        """
        return float(np.max(np.abs(self.L.constraints(q))))

    def energy(self, q: np.ndarray, v: np.ndarray) -> float:
        """Kinetic + gravity + spring energy (J).

        Args:
            q: reference-point coordinates (3 per link).
            v: their rates.

        Returns:
            The energy, J.
        """
        return float(sum(self.L.energy(q, v).values()))

    def joint_angles(self, q: np.ndarray) -> np.ndarray:
        """The 9 tree-joint angles in `JOINT_ORDER` (rad) of reference-point coordinates q.

        Args:
            q: reference-point coordinates (3 per link).

        Returns:
            (9,) angles, rad.
        """
        angles = joint_angles_from_lagrange(q)
        return np.array([angles[j] for j in JOINT_ORDER])


class LagrangeJointDeployment:
    """The same Lagrange first-kind dynamics with the state in tree-joint coordinates (`JOINT_ORDER`).

    Each evaluation maps the joint state to reference-point coordinates by numpy forward
    kinematics, solves A f = P, and returns the joint accelerations (differences of the links'
    absolute angular accelerations). Integrated by `integrate` in the same coordinates as
    `PinocchioDeployment`, the two discrete trajectories differ only by the solvers' round-off,
    not by the integrator's truncation error.
    """

    def __init__(self, params: TenBarParams) -> None:
        self.p = params
        self.inner = LagrangeDeployment(params)
        self.L = self.inner.L
        hinges = geo.hinges(params)[: len(JOINT_ORDER)]
        index = {b: i for i, b in enumerate(geo.BODIES)}
        self.joint_rows = np.zeros((len(JOINT_ORDER), self.L.n))  # joint angle = row . q_L
        for h in hinges:
            k = JOINT_ORDER.index(h.name)
            self.joint_rows[k, 3 * index[h.child] + 2] = 1.0
            if h.parent is not None:
                self.joint_rows[k, 3 * index[h.parent] + 2] = -1.0
        self.motor_rows = np.array([JOINT_ORDER.index(m) for m in MOTORS])
        self.fk = TreeKinematics(params)

    def _state(self, q, v):
        return self.fk(q, v)

    def _map(self, q):
        """(q_L, T) with T = d q_L / d q (the forward kinematics is linear in the rates)."""
        return self.fk(q, np.eye(len(q)))

    def rhs(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        """(joint accelerations, motor torques (R1, R3) N m, net external power W) at time t (s).

        Args:
            t: time, s.
            q: the 9 joint angles in `JOINT_ORDER` (rad).
            v: their rates.

        Returns:
            (accelerations, motor torques (R1, R3) N m, net external power W).
        """
        qL, vL = self._state(q, v)
        qdd, u, power = self.inner.rhs(t, qL, vL)
        return self.joint_rows @ qdd, u, power

    def _rows(self, t, q):
        pos, _, _ = motor_law(self.p, t)
        qL, T = self._map(q)
        e = np.concatenate([self.L.constraints(qL), q[self.motor_rows] - pos])
        return e, np.vstack([self.L.jacobian(qL) @ T, np.eye(len(q))[self.motor_rows]])

    def project(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(q, v) on the pin constraints and the motor laws at time t (s).

        Args:
            t: time, s.
            q: the 9 joint angles in `JOINT_ORDER` (rad).
            v: their rates.

        Returns:
            (q, v) on the constraints and the motor laws at t.

        Raises:
            ClosureNotConverged: the projection does not converge.
        """
        _, rate, _ = motor_law(self.p, t)
        return project(lambda x: self._rows(t, x), q, v, rate, "ten-bar projection (Lagrange, joints)")

    def residual(self, t: float, q: np.ndarray) -> float:
        """Largest pin-constraint residual (m) at joint angles q.

        Args:
            t: time, s.
            q: the 9 joint angles in `JOINT_ORDER` (rad).

        Returns:
            The residual, m.
        """
        return self.inner.residual(t, self._state(q, 0 * q)[0])

    def energy(self, q: np.ndarray, v: np.ndarray) -> float:
        """Kinetic + gravity + spring energy (J).

        Args:
            q: the 9 joint angles in `JOINT_ORDER` (rad).
            v: their rates.

        Returns:
            The energy, J.
        """
        return self.inner.energy(*self._state(q, v))

    def joint_angles(self, q: np.ndarray) -> np.ndarray:
        """The joint angles themselves (rad, `JOINT_ORDER`).

        Args:
            q: the 9 joint angles in `JOINT_ORDER` (rad).

        Returns:
            (9,) angles, rad.
        """
        return q.copy()
