"""Lagrange equations of the first kind for planar pin-jointed linkages, numpy and scipy only.

The method of patent CN105975733 (ten-bar solar-array linkage): every moving link i has the
coordinates (x_i, z_i, phi_i), its centre of mass in the world x-z plane and its absolute angle
(from +x towards +z), so the mass matrix is the constant diagonal M = diag(m_i, m_i, J_i). Each
revolute pair k between links a and b adds two constraint rows

    C_k(q) = r_a + R(phi_a) s_a - r_b - R(phi_b) s_b = 0        (s: the pin seen from each COM),

a wall pin has a fixed point in place of link a. A motor on pair k prescribes the relative angle
phi_b - phi_a = psi(t) and applies the unknown torque u (on b, -u on a). With the multipliers
lambda the equations of motion and the acceleration-level constraints are

    M qdd + C_q^T lambda - S^T u = Q(q, qd)      C_q qdd = gamma(q, qd)      S qdd = psi_dd(t),

gathered, as in the patent, into A f = P with f = [qdd, lambda, u] and solved f = A^-1 P.

Sign conventions: lambda_k (2,) is the force (N) that link a (the parent side) exerts on link b at
the pin, world x-z; u is a torque (N m) from +x towards +z, i.e. about -y of the world.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg

from mechkit.base.exceptions import ClosureNotConverged, InvalidParameters, SingularConfiguration

__all__ = ["Body", "Linkage", "Pin", "Solution", "Spring"]

_E = np.array([[0.0, -1.0], [1.0, 0.0]])  # d R(phi)/d phi = E R(phi)


def _rot(phi: float) -> np.ndarray:
    c, s = np.cos(phi), np.sin(phi)
    return np.array([[c, -s], [s, c]])


@dataclass(frozen=True)
class Body:
    """A rigid link: mass (kg), inertia about its COM normal to the plane (kg m^2), COM in its frame (m)."""

    name: str
    mass: float
    inertia: float
    com: np.ndarray


@dataclass(frozen=True)
class Pin:
    """A revolute pair: `a` (body index, None = the wall) and `b`; points in their body frames (m).

    For the wall, `point_a` is the fixed world point.
    """

    name: str
    a: int | None
    point_a: np.ndarray
    b: int
    point_b: np.ndarray


@dataclass(frozen=True)
class Spring:
    """A torsion spring-damper on a pin: torque on b = k (free_angle - rel) - c rel_dot (N m)."""

    pin: str
    stiffness: float
    free_angle: float
    damping: float = 0.0


@dataclass(frozen=True)
class Solution:
    """One solve of A f = P: accelerations (3 per body), multipliers (pin -> (2,) N), motor torques (N m)."""

    qdd: np.ndarray
    forces: dict[str, np.ndarray]
    efforts: dict[str, float]
    condition: float  # ratio of the largest to the smallest LU pivot of A


@dataclass
class Linkage:
    """A planar linkage in reference-point coordinates with prescribed motors.

    Attributes:
        bodies: the links; coordinate block i is (x_i, z_i, phi_i).
        pins: the revolute pairs.
        motors: names of the pins whose relative angle is prescribed (their torque is solved).
        springs: torsion springs on pins.
        gravity: (2,) m/s^2 in the x-z plane.
    """

    bodies: Sequence[Body]
    pins: Sequence[Pin]
    motors: Sequence[str] = ()
    springs: Sequence[Spring] = ()
    gravity: np.ndarray = field(default_factory=lambda: np.array([0.0, -9.81]))

    def __post_init__(self) -> None:
        self.n = 3 * len(self.bodies)
        self.pin_index = {p.name: i for i, p in enumerate(self.pins)}
        for name in list(self.motors) + [s.pin for s in self.springs]:
            if name not in self.pin_index:
                raise InvalidParameters("pin", name, f"no such pin; pins: {list(self.pin_index)}")
        masses = np.array([[b.mass, b.mass, b.inertia] for b in self.bodies]).ravel()
        if np.any(masses <= 0):
            raise InvalidParameters("bodies", masses.tolist(), "masses and inertias must be > 0")
        self.mass_diag = masses
        self.S = np.array([self._relative_row(self.pins[self.pin_index[m]]) for m in self.motors]).reshape(-1, self.n)

    # ------------------------------------------------------------ geometry
    def _relative_row(self, pin: Pin) -> np.ndarray:
        """Row r with r . q = phi_b - phi_a."""
        row = np.zeros(self.n)
        row[3 * pin.b + 2] = 1.0
        if pin.a is not None:
            row[3 * pin.a + 2] = -1.0
        return row

    def relative_angle(self, q: np.ndarray, pin: str) -> float:
        """phi_b - phi_a of a pin (phi_a = 0 for the wall); of rates, its rate.

        Args:
            q: (3 * bodies,) reference-point coordinates (x, z in m, phi in rad per body).
            pin: the pin's name.

        Returns:
            The angle (rad) (or its rate, rad/s, given rates).
        """
        return float(self._relative_row(self.pins[self.pin_index[pin]]) @ q)

    def _arm(self, q: np.ndarray, body: int, point: np.ndarray) -> np.ndarray:
        """World vector (2,) from a body's COM to one of its points."""
        return _rot(q[3 * body + 2]) @ (point - self.bodies[body].com)

    def point(self, q: np.ndarray, body: int, point: np.ndarray) -> np.ndarray:
        """World position (m) of a body-frame point.

        Args:
            q: (3 * bodies,) reference-point coordinates (x, z in m, phi in rad per body).
            body: the body's index.
            point: the point (2,) in the body frame, m.

        Returns:
            Its world position (x, z), m.
        """
        return q[3 * body : 3 * body + 2] + self._arm(q, body, point)

    def constraints(self, q: np.ndarray) -> np.ndarray:
        """The pin residuals C(q).

        Args:
            q: (3 * bodies,) reference-point coordinates (x, z in m, phi in rad per body).

        Returns:
            (2 * pins,) residuals, m.
        """
        out = np.empty(2 * len(self.pins))
        for k, p in enumerate(self.pins):
            pa = p.point_a if p.a is None else self.point(q, p.a, p.point_a)
            out[2 * k : 2 * k + 2] = pa - self.point(q, p.b, p.point_b)
        return out

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        """The constraint Jacobian C_q.

        Args:
            q: (3 * bodies,) reference-point coordinates (x, z in m, phi in rad per body).

        Returns:
            (2 * pins, 3 * bodies) matrix.
        """
        Cq = np.zeros((2 * len(self.pins), self.n))
        for k, p in enumerate(self.pins):
            rows = slice(2 * k, 2 * k + 2)
            if p.a is not None:
                Cq[rows, 3 * p.a : 3 * p.a + 2] = np.eye(2)
                Cq[rows, 3 * p.a + 2] = _E @ self._arm(q, p.a, p.point_a)
            Cq[rows, 3 * p.b : 3 * p.b + 2] = -np.eye(2)
            Cq[rows, 3 * p.b + 2] = -_E @ self._arm(q, p.b, p.point_b)
        return Cq

    def gamma(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """Right side of C_q qdd = gamma: the velocity terms of the second derivative of C.

        Args:
            q: (3 * bodies,) reference-point coordinates (x, z in m, phi in rad per body).
            qd: (3 * bodies,) their rates (m/s, rad/s).

        Returns:
            (2 * pins,) m/s^2.
        """
        out = np.empty(2 * len(self.pins))
        for k, p in enumerate(self.pins):
            g = -self._arm(q, p.b, p.point_b) * qd[3 * p.b + 2] ** 2
            if p.a is not None:
                g = g + self._arm(q, p.a, p.point_a) * qd[3 * p.a + 2] ** 2
            out[2 * k : 2 * k + 2] = g
        return out

    # ------------------------------------------------------------ forces and energy
    def applied(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """Generalised applied forces Q: gravity and springs (N, N m).

        Args:
            q: (3 * bodies,) reference-point coordinates (x, z in m, phi in rad per body).
            qd: (3 * bodies,) their rates (m/s, rad/s).

        Returns:
            (3 * bodies,) generalised forces (N, N m).
        """
        Q = np.zeros(self.n)
        for i, b in enumerate(self.bodies):
            Q[3 * i : 3 * i + 2] = b.mass * self.gravity
        for s in self.springs:
            row = self._relative_row(self.pins[self.pin_index[s.pin]])
            Q += row * (s.stiffness * (s.free_angle - row @ q) - s.damping * (row @ qd))
        return Q

    def energy(self, q: np.ndarray, qd: np.ndarray) -> dict[str, float]:
        """Kinetic, gravity and spring energy (J).

        Args:
            q: (3 * bodies,) reference-point coordinates (x, z in m, phi in rad per body).
            qd: (3 * bodies,) their rates (m/s, rad/s).

        Returns:
            {"kinetic", "gravity", "spring"} -> energy (J).
        """
        kinetic = 0.5 * float(qd @ (self.mass_diag * qd))
        gravity = -sum(b.mass * float(self.gravity @ q[3 * i : 3 * i + 2]) for i, b in enumerate(self.bodies))
        spring = sum(0.5 * s.stiffness * (self.relative_angle(q, s.pin) - s.free_angle) ** 2 for s in self.springs)
        return {"kinetic": kinetic, "gravity": gravity, "spring": spring}

    def power(self, q: np.ndarray, qd: np.ndarray, efforts: dict[str, float]) -> dict[str, float]:
        """Motor power in and damper power out (W).

        Args:
            q: (3 * bodies,) reference-point coordinates (x, z in m, phi in rad per body).
            qd: (3 * bodies,) their rates (m/s, rad/s).
            efforts: motor -> torque (N m).

        Returns:
            {"motor": power in, "damper": power out} (W).
        """
        motor = sum(u * self.relative_angle(qd, m) for m, u in efforts.items())
        damper = sum(s.damping * self.relative_angle(qd, s.pin) ** 2 for s in self.springs)
        return {"motor": motor, "damper": damper}

    # ------------------------------------------------------------ the patent's A f = P
    def solve(self, q: np.ndarray, qd: np.ndarray, motor_acc: Sequence[float] = ()) -> Solution:
        """Accelerations, pin forces and motor torques at (q, qd) for prescribed motor accelerations.

        Args:
            q: (3 * bodies,) reference-point coordinates (x, z in m, phi in rad per body).
            qd: (3 * bodies,) their rates (m/s, rad/s).
            motor_acc: the motors' angular accelerations (rad/s^2), in the order of `motors`.

        Returns:
            The accelerations qdd (3 * bodies,), every pin's force (N, world x-z) and the motors' torques (N m).

        Raises:
            SingularConfiguration: A is singular (a loop at a dead-centre pose, or motors that do
                not fit the mobility).
        """
        n, m, d = self.n, 2 * len(self.pins), len(self.motors)
        Cq = self.jacobian(q)
        A = np.zeros((n + m + d, n + m + d))
        A[:n, :n] = np.diag(self.mass_diag)
        A[:n, n : n + m] = Cq.T
        A[:n, n + m :] = -self.S.T
        A[n : n + m, :n] = Cq
        A[n + m :, :n] = self.S
        P = np.concatenate([self.applied(q, qd), self.gamma(q, qd), np.asarray(motor_acc, dtype=float)])
        with warnings.catch_warnings():  # a zero pivot is reported below, with the matrix named
            warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)
            lu, piv = scipy.linalg.lu_factor(A, check_finite=False)
        pivots = np.abs(np.diag(lu))
        cond = float(pivots.max() / max(pivots.min(), 1e-300))  # pivot ratio: a cheap conditioning estimate
        if not np.isfinite(cond) or cond > 1e12:
            raise SingularConfiguration(cond, "Lagrange first-kind matrix A (pivot ratio)")
        f = scipy.linalg.lu_solve((lu, piv), P, check_finite=False)
        lam = f[n : n + m].reshape(-1, 2)
        return Solution(
            f[:n],
            {p.name: lam[k] for k, p in enumerate(self.pins)},
            {name: float(u) for name, u in zip(self.motors, f[n + m :])},
            float(cond),
        )

    def forward(self, q: np.ndarray, qd: np.ndarray, efforts: Sequence[float] = ()) -> np.ndarray:
        """Accelerations (3 per body) under given motor torques, the motors' angles left free:
        `[M, C_q^T; C_q, 0] [qdd; lambda] = [Q + S^T u; gamma]`.

        Args:
            q: (3 * bodies,) reference-point coordinates (m, rad).
            qd: (3 * bodies,) their rates.
            efforts: torques u (N m) of `motors`, in order.

        Returns:
            qdd (3 * bodies,), m/s^2 and rad/s^2.

        Raises:
            numpy.linalg.LinAlgError: the system is singular (a loop at a dead-centre pose).
        """
        n, m = self.n, 2 * len(self.pins)
        Cq = self.jacobian(q)
        K = np.zeros((n + m, n + m))
        K[:n, :n] = np.diag(self.mass_diag)
        K[:n, n:] = Cq.T
        K[n:, :n] = Cq
        rhs = np.concatenate([self.applied(q, qd) + self.S.T @ np.asarray(efforts, dtype=float), self.gamma(q, qd)])
        return np.linalg.solve(K, rhs)[:n]

    # ------------------------------------------------------------ the constraint manifold
    def project(
        self,
        q: np.ndarray,
        qd: np.ndarray,
        motor_pos: Sequence[float] = (),
        motor_vel: Sequence[float] = (),
        tol: float = 1e-13,
        max_iter: int = 20,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Minimum-norm projection onto C = 0, S q = psi (Gauss-Newton), then C_q qd = 0, S qd = psi_dot.

        Args:
            q: (3 * bodies,) reference-point coordinates (x, z in m, phi in rad per body).
            qd: (3 * bodies,) their rates (m/s, rad/s).
            motor_pos: the motors' angles (rad) to hold, in the order of `motors`.
            motor_vel: their rates (rad/s).
            tol: the position residual reached (m).
            max_iter: Gauss-Newton steps at most.

        Returns:
            (q, qd) on the constraint manifold.

        Raises:
            ClosureNotConverged: the position projection does not reach tol.
        """
        q = q.copy()
        target = np.asarray(motor_pos, dtype=float)
        for it in range(max_iter):  # at least two Gauss-Newton steps: land on the manifold, not near it
            e = np.concatenate([self.constraints(q), self.S @ q - target])
            if it >= 2 and np.linalg.norm(e) <= tol:
                break
            G = np.vstack([self.jacobian(q), self.S])
            q -= np.linalg.lstsq(G, e, rcond=None)[0]
        else:
            raise ClosureNotConverged(float(np.linalg.norm(e)), tol, max_iter, "Lagrange coordinates projection")
        G = np.vstack([self.jacobian(q), self.S])
        err = G @ qd - np.concatenate([np.zeros(2 * len(self.pins)), np.asarray(motor_vel, dtype=float)])
        return q, qd - np.linalg.lstsq(G, err, rcond=None)[0]
