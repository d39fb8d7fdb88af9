"""The classic fourth-order Runge-Kutta method at a fixed step, as a scipy `OdeSolver` (so that the
simulator's stepper, events and dense output take it as they take scipy's own methods).

Why: the field compares simulators at the same fixed step and the same order (MuJoCo's `RK4`
integrator is this method); scipy offers no fixed-step method, and its adaptive pairs with the error
control off cost 6 (RK45) or 12 (DOP853) evaluations a step where RK4 takes 4.

Step from (t, y) with h: k1 = f(t, y), k2 = f(t + h/2, y + h k1/2), k3 = f(t + h/2, y + h k2/2),
k4 = f(t + h, y + h k3), y1 = y + h (k1 + 2 k2 + 2 k3 + k4) / 6 (Kutta 1901; Hairer, Norsett, Wanner,
"Solving ODEs I", table 1.2). Dense output: the method's third-order continuous extension (same book,
II.6, eq. 6.18 with the classic coefficients), y(t + theta h) = y + h sum_i b_i(theta) k_i with
b1 = theta - 3 theta^2/2 + 2 theta^3/3, b2 = b3 = theta^2 - 2 theta^3/3, b4 = -theta^2/2 + 2 theta^3/3:
no extra evaluation, equal to y1 at theta = 1.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from scipy.integrate import DenseOutput, OdeSolver


class RK4(OdeSolver):
    """Classic RK4 at the fixed step `max_step` (scipy's `OdeSolver` interface).

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
            raise ValueError(f"RK4 needs a fixed step: max_step = {max_step}")
        self.h = float(max_step)
        self.k = np.empty((4, self.n))

    def _step_impl(self):
        t, y, h = self.t, self.y, min(self.h, abs(self.t_bound - self.t)) * self.direction
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
