"""Fixed-step one-step methods as scipy `OdeSolver`s (so that the simulator's stepper, events and dense
output take them as they take scipy's own): the classic RK4, semi-implicit (symplectic) Euler and the
implicit midpoint rule.

Why: the field compares simulators at the same fixed step and the same order (MuJoCo's `RK4` integrator
is the classic RK4, its `Euler` the semi-implicit Euler); scipy offers no fixed-step method, and its
adaptive pairs with the error control off cost 6 (RK45) or 12 (DOP853) evaluations a step where RK4
takes 4 and semi-implicit Euler 1. Stiff problems (a steep friction regularisation, a stiff spring) need
an implicit method; scipy's Radau with its error control off is not a fixed-step method (its Newton
iteration and step rejections still act), so the implicit midpoint rule is offered: A-stable, symmetric,
symplectic, order 2 (the one-stage Gauss method).

- RK4 (Kutta 1901; Hairer, Norsett, Wanner, "Solving ODEs I", table 1.2): k1 = f(t, y),
  k2 = f(t + h/2, y + h k1/2), k3 = f(t + h/2, y + h k2/2), k4 = f(t + h, y + h k3),
  y1 = y + h (k1 + 2 k2 + 2 k3 + k4) / 6. Dense output: its third-order continuous extension (same book,
  II.6, eq. 6.18), y(t + theta h) = y + h sum_i b_i(theta) k_i with b1 = theta - 3 theta^2/2 + 2 theta^3/3,
  b2 = b3 = theta^2 - 2 theta^3/3, b4 = -theta^2/2 + 2 theta^3/3: no extra evaluation, y1 at theta = 1.
- Semi-implicit Euler (Hairer, Lubich, Wanner, "Geometric Numerical Integration", I.1.2, eq. 1.10):
  for y = [x (m), u (m), w] with dx/dt = u: k = f(t, y); u1 = u + h k_u, x1 = x + h u1, w1 = w + h k_w
  (the works ride along explicitly). Order 1, one evaluation a step. It needs `npos` = m: the simulator's
  position part (q itself on revolute and prismatic joints, else a tangent offset that each restart sets
  to 0, where its derivative is v too).
- Implicit midpoint (same book, I.1.2 and II.1.1): y1 = y + h f(t + h/2, z), z = (y + y1)/2, solved for z
  by simplified Newton iterations on G(z) = z - y - (h/2) f(t + h/2, z) with the Jacobian of f by forward
  differences (`FD_STEP`), factored once and kept over the steps until an iteration stops contracting
  (`NEWTON_RATE`) or runs out (`NEWTON_ITERATIONS`); then it is computed again at the step's start, and a
  step whose iteration still fails stops the run. Order 2. Its dense output is its collocation
  polynomial, linear on the step (the one-stage Gauss method's), as semi-implicit Euler's.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import scipy.linalg
from scipy.integrate import DenseOutput, OdeSolver

#: Newton increment (relative to 1 + |z|, per component) at which the implicit midpoint's iteration stops (ours).
NEWTON_TOL = 1e-12
#: Newton iterations of one step before its Jacobian is computed again (ours).
NEWTON_ITERATIONS = 8
#: Largest ratio of successive Newton increments with a kept Jacobian (ours: above it, a fresh one).
NEWTON_RATE = 0.5
#: Forward-difference step of the Jacobian, relative to 1 + |y_i| (ours: about the square root of the
#: machine epsilon).
FD_STEP = 1.5e-8


class FixedStep(OdeSolver):
    """A one-step method at the fixed step `max_step` (scipy's `OdeSolver` interface), restartable in place.

    Args:
        fun: dy/dt = fun(t, y).
        t0: the initial time (s).
        y0: (n,) the initial state.
        t_bound: the end time (s); the last step is shortened to end there.
        max_step: the fixed step h (s, > 0, finite).
        **extraneous: scipy's tolerance arguments (`rtol`, `atol`, `first_step`), ignored: the step
            is fixed and no error is estimated.

    Raises:
        ValueError: a step that is not a positive finite number.
    """

    def __init__(
        self,
        fun: Callable[[float, np.ndarray], np.ndarray],
        t0: float,
        y0: np.ndarray,
        t_bound: float,
        max_step: float = np.inf,
        **extraneous: Any,
    ):
        super().__init__(fun, t0, y0, t_bound, vectorized=False)
        if not (0 < max_step < np.inf):
            raise ValueError(f"{type(self).__name__} needs a fixed step: max_step = {max_step}")
        self.h = float(max_step)

    def reset(self, t: float, y: np.ndarray) -> None:
        """Start again from (t, y) with the same step and end (no evaluation: a fixed-step method keeps no
        memory of the past steps but what it chooses to, as the implicit midpoint's Jacobian).

        Args:
            t: the time (s).
            y: (n,) the state.
        """
        self.t, self.y, self.t_old, self.status = float(t), np.array(y, dtype=float), None, "running"

    def _size(self) -> float:
        """This step's signed size (the last one shortened to end on `t_bound`)."""
        return min(self.h, abs(self.t_bound - self.t)) * self.direction


class RK4(FixedStep):
    """The classic RK4 at a fixed step (see the module docstring; arguments as `FixedStep`'s)."""

    def __init__(
        self,
        fun: Callable[[float, np.ndarray], np.ndarray],
        t0: float,
        y0: np.ndarray,
        t_bound: float,
        max_step: float = np.inf,
        **extraneous: Any,
    ):
        super().__init__(fun, t0, y0, t_bound, max_step)
        self.k = np.empty((4, self.n))

    def _step_impl(self):
        t, y, h = self.t, self.y, self._size()
        k = self.k
        k[0] = self.fun(t, y)  # at the step's start: the simulator restarts from the projected state
        k[1] = self.fun(t + h / 2, y + h / 2 * k[0])
        k[2] = self.fun(t + h / 2, y + h / 2 * k[1])
        k[3] = self.fun(t + h, y + h * k[2])
        self.y_old = y
        self.t, self.y = t + h, y + h / 6 * (k[0] + 2 * k[1] + 2 * k[2] + k[3])
        return True, None

    def _dense_output_impl(self):
        return RK4Dense(self.t_old, self.t, self.y_old, self.k.copy())


class SymplecticEuler(FixedStep):
    """Semi-implicit (symplectic) Euler at a fixed step (see the module docstring).

    Args:
        fun: dy/dt = fun(t, y).
        t0: the initial time (s).
        y0: (n,) the initial state, [x (npos), u (npos), the rest].
        t_bound: the end time (s).
        max_step: the fixed step h (s).
        npos: the size of the position part x (dx/dt = u, the next npos components).
        **extraneous: scipy's tolerance arguments, ignored.

    Raises:
        ValueError: no fixed step, or no position part that fits y.
    """

    def __init__(
        self,
        fun: Callable[[float, np.ndarray], np.ndarray],
        t0: float,
        y0: np.ndarray,
        t_bound: float,
        max_step: float = np.inf,
        npos: int | None = None,
        **extraneous: Any,
    ):
        super().__init__(fun, t0, y0, t_bound, max_step)
        if npos is None or not 0 < 2 * npos <= self.n:
            raise ValueError(f"SymplecticEuler needs its position part: npos = {npos} for a state of {self.n}")
        self.npos = int(npos)

    def _step_impl(self):
        t, y, h, m = self.t, self.y, self._size(), self.npos
        k = self.fun(t, y)
        y1 = y + h * k
        y1[:m] = y[:m] + h * y1[m : 2 * m]  # the positions move with the new velocities
        self.y_old, self.t, self.y = y, t + h, y1
        return True, None

    def _dense_output_impl(self):
        return LinearDense(self.t_old, self.t, self.y_old, self.y)


class ImplicitMidpoint(FixedStep):
    """The implicit midpoint rule at a fixed step, simplified Newton on a finite-difference Jacobian (see the
    module docstring; arguments as `FixedStep`'s)."""

    def __init__(
        self,
        fun: Callable[[float, np.ndarray], np.ndarray],
        t0: float,
        y0: np.ndarray,
        t_bound: float,
        max_step: float = np.inf,
        **extraneous: Any,
    ):
        super().__init__(fun, t0, y0, t_bound, max_step)
        self.lu: tuple | None = None
        self.lu_h = 0.0
        self.slope: np.ndarray | None = None
        self.jacobians = 0

    def _factor(self, t: float, y: np.ndarray, h: float) -> None:
        """The Jacobian of f at (t, y) by forward differences, I - (h/2) J factored."""
        f0 = self.fun(t, y)
        J = np.empty((self.n, self.n))
        for i in range(self.n):
            dy = FD_STEP * (1.0 + abs(y[i]))
            yp = y.copy()
            yp[i] += dy
            J[:, i] = (self.fun(t, yp) - f0) / dy
        self.lu, self.lu_h, self.slope = scipy.linalg.lu_factor(np.eye(self.n) - 0.5 * h * J), h, f0
        self.jacobians += 1

    def _newton(self, t: float, y: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray] | None:
        """z and the step's slope f(t + h/2, z) by simplified Newton from the last slope's predictor (the slope
        taken at the iterate before the last increment, which is below `NEWTON_TOL`), or None (no contraction)."""
        z = y + 0.5 * h * self.slope
        last = np.inf
        for _ in range(NEWTON_ITERATIONS):
            f = self.fun(t + 0.5 * h, z)
            dz = scipy.linalg.lu_solve(self.lu, y + 0.5 * h * f - z)
            z = z + dz
            size = float(np.max(np.abs(dz) / (1.0 + np.abs(z))))
            if not np.isfinite(size) or size > NEWTON_RATE * last:
                return None
            if size <= NEWTON_TOL:  # f at the last iterate but one: off by the Jacobian times this increment
                return z, f
            last = size
        return None

    def _step_impl(self):
        t, y, h = self.t, self.y, self._size()
        if self.lu is None or self.lu_h != h:
            self._factor(t, y, h)
        solved = self._newton(t, y, h)
        if solved is None:
            self._factor(t, y, h)
            solved = self._newton(t, y, h)
        if solved is None:
            return False, f"the implicit midpoint's Newton iteration does not converge at step {h:.3g} s"
        f = solved[1]
        self.slope = f
        self.y_old, self.t, self.y = y, t + h, y + h * f
        return True, None

    def _dense_output_impl(self):
        return LinearDense(self.t_old, self.t, self.y_old, self.y)


class RK4Dense(DenseOutput):
    """RK4's third-order continuous extension on one step (see the module docstring).

    Args:
        t_old: the step's start (s).
        t: its end (s).
        y_old: (n,) the state at its start.
        k: (4, n) the step's stages.
    """

    def __init__(self, t_old: float, t: float, y_old: np.ndarray, k: np.ndarray):
        super().__init__(t_old, t)
        self.h, self.y_old, self.k = t - t_old, y_old, k

    def _call_impl(self, t):
        theta = (np.asarray(t, dtype=float) - self.t_old) / self.h
        b1 = theta - 1.5 * theta**2 + 2 / 3 * theta**3
        b23 = theta**2 - 2 / 3 * theta**3
        b4 = -0.5 * theta**2 + 2 / 3 * theta**3
        k = self.k
        step = np.multiply.outer(k[0], b1) + np.multiply.outer(k[1] + k[2], b23) + np.multiply.outer(k[3], b4)
        return (self.y_old[:, None] if step.ndim == 2 else self.y_old) + self.h * step


class LinearDense(DenseOutput):
    """The straight line between a step's ends (the first-order methods' and the midpoint rule's own).

    Args:
        t_old: the step's start (s).
        t: its end (s).
        y_old: (n,) the state at its start.
        y: (n,) the state at its end.
    """

    def __init__(self, t_old: float, t: float, y_old: np.ndarray, y: np.ndarray):
        super().__init__(t_old, t)
        self.y_old, self.dy = y_old, y - y_old

    def _call_impl(self, t):
        theta = (np.asarray(t, dtype=float) - self.t_old) / (self.t - self.t_old)
        return (self.y_old[:, None] + np.multiply.outer(self.dy, theta)) if theta.ndim else self.y_old + theta * self.dy
