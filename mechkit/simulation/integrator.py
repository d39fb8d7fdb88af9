"""Time stepping: scipy's one-step integrators, one accepted step at a time, restarted from the projected
state after each step, with events located on the step's dense output.

Why scipy.integrate: it is maintained, its explicit Runge-Kutta pairs (RK45 = Dormand-Prince 5(4),
the default; DOP853; RK23) control the local error at the tolerances given, and each step has a dense
output to locate events on. It also has an implicit one-step method (Radau IIA, order 5) for stiff
cases (a steep friction regularisation). The DAE integrators available from PyPI were not better
here: assimulo's last release (3.0, 2018) builds against a SUNDIALS install, and CasADi's IDAS needs
the equations as CasADi expressions, not Pinocchio's calls. Multistep methods (BDF, LSODA) are not
offered: their history cannot survive the projection after every step.

After every accepted step the caller projects the state onto the constraint manifold; the solver is
then restarted from the projected state with the step size it had chosen (a Runge-Kutta pair carries
no other memory; one extra evaluation per step, the first stage at the new state). Radau (Radau IIA,
implicit) carries more: its Jacobian, the LU factors of its Newton matrices, its step controller's history
and the last step's collocation polynomial, from which it predicts the next step's Newton start. Where it
restarts at the end of its own step (no event cut the step short), it keeps them and only takes the
projected state and its derivative, its Jacobian marked stale (re-evaluated where Newton converges
slowly, as scipy does between steps): a new solver would evaluate a Jacobian at every step and start
Newton from zero. A fixed step `dt`
runs the same pair with its error control off (first and largest step dt, an absolute tolerance of 1e300): the
speed comparison with MuJoCo and the ten-bar's step-size studies use it. The fixed-step methods
(`mechkit.simulation.fixed_step`: the classic RK4, MuJoCo's RK4; semi-implicit Euler, MuJoCo's Euler; the
implicit midpoint rule for stiff problems) run at a fixed step only; they are restarted in place (no
evaluation, no new solver: a restart at a fixed step costs nothing).

Events: after a step from (t0, y0) to (t1, y1), each event function g(t, y) is evaluated at both
ends; where its sign changes in the event's direction, the crossing is found by Brent's method
(`scipy.optimize.brentq`) on the dense output, and the earliest crossing ends the step there.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import scipy.integrate
import scipy.optimize

from mechkit.base.exceptions import InvalidParameters, MechkitError
from mechkit.simulation.fixed_step import RK4, FixedStep, ImplicitMidpoint, SymplecticEuler

#: The one-step methods offered (scipy.integrate classes).
METHODS = {
    "RK45": scipy.integrate.RK45,
    "DOP853": scipy.integrate.DOP853,
    "RK23": scipy.integrate.RK23,
    "Radau": scipy.integrate.Radau,
    "RK4": RK4,
    "SymplecticEuler": SymplecticEuler,
    "ImplicitMidpoint": ImplicitMidpoint,
}
#: Methods without an error estimate: they need a fixed step.
FIXED_ONLY = ("RK4", "SymplecticEuler", "ImplicitMidpoint")
#: Methods that need the size of the position part of y (`Options.npos`).
SECOND_ORDER = ("SymplecticEuler",)
#: Default relative and absolute tolerances of the adaptive steps (ours: the energy balance of the
#: registered mechanisms then holds to about 1e-8 of the energy exchanged).
RTOL, ATOL = 1e-9, 1e-11
#: Absolute tolerance that switches the error control off at a fixed step (every step accepted; finite,
#: so that scipy's error scale atol + rtol |y| stays a number where y is 0).
FIXED_ATOL = 1e300
#: Time (s) within which an event's crossing is located.
EVENT_XTOL = 1e-12

Function = Callable[[float, np.ndarray], np.ndarray]


class IntegrationFailed(MechkitError):
    """The integrator could not take a step: the step size collapsed (scipy's message) or the steps ran out.

    Attributes:
        t: the time reached (s).
        why: scipy's message or the reason.
        joint: the joint moving most along the freedom closest to opening there (the closure rows'
            weakest direction), or "" where not known.
    """

    def __init__(self, t: float, why: str, joint: str = ""):
        self.t, self.why, self.joint = t, why, joint
        where = f" (joint {joint!r} along the closure rows' weakest direction)" if joint else ""
        super().__init__(f"the integrator stopped at t = {t:.6g} s: {why}{where}")


@dataclass(frozen=True)
class Options:
    """How to step.

    Attributes:
        method: one of `METHODS`.
        rtol: the adaptive steps' relative tolerance (scipy's meaning).
        atol: their absolute tolerance (scipy's meaning).
        dt: a fixed step (s), or None for adaptive steps.
        max_step: the largest adaptive step (s).
        npos: the size of the position part of y, followed by as many velocities (`SECOND_ORDER` methods).
    """

    method: str = "RK45"
    rtol: float = RTOL
    atol: float = ATOL
    dt: float | None = None
    max_step: float = math.inf
    npos: int | None = None

    def __post_init__(self) -> None:
        if self.method not in METHODS:
            raise InvalidParameters("method", self.method, f"expected one of {', '.join(METHODS)}")
        if self.dt is None and self.method in FIXED_ONLY:
            raise InvalidParameters("method", self.method, "estimates no error: give a fixed step dt")
        if self.dt is not None and not (self.dt > 0 and math.isfinite(self.dt)):
            raise InvalidParameters("dt", self.dt, "a fixed step must be a positive number of seconds")
        if self.method in SECOND_ORDER and self.npos is None:
            raise InvalidParameters("method", self.method, "needs the position part of the state (npos)")
        if not (self.rtol > 0 and self.atol > 0 and self.max_step > 0):
            raise InvalidParameters("rtol/atol/max_step", (self.rtol, self.atol, self.max_step), "must be > 0")


@dataclass(frozen=True)
class Event:
    """A scalar function of the state whose sign change ends a step.

    Attributes:
        name: for reports.
        fn: g(t, y) (any unit).
        direction: +1 (from negative to positive), -1 (positive to negative) or 0 (either).
    """

    name: str
    fn: Function
    direction: int = 0


class Stepper:
    """Accepted steps of a scipy one-step method, restarted from any state.

    Args:
        fun: dy/dt = fun(t, y).
        t_end: the end time (s).
        options: how to step.
        jacobian: () -> the Jacobian (t, y) -> d fun/dy that "Radau" uses from the next restart on, or None
            for scipy's differences (`mechkit.simulation.jacobian`); None: always scipy's.
    """

    def __init__(
        self, fun: Function, t_end: float, options: Options, jacobian: Callable[[], Callable | None] | None = None
    ):
        self.fun, self.t_end, self.options, self.jacobian = fun, t_end, options, jacobian
        self.solver = None
        self.h: float | None = options.dt
        self._jac: Callable | None = None

    def restart(self, t: float, y: np.ndarray) -> None:
        """Start again from a state with the last step size (the first evaluation of fun is there).

        Args:
            t: the time (s).
            y: the integrated vector at t.
        """
        o, remaining = self.options, self.t_end - t
        first = None if self.h is None else min(self.h, remaining)
        jac = self.jacobian() if o.method == "Radau" and self.jacobian is not None else None
        extra = {"jac": jac} if jac is not None else {}
        s = self.solver
        if isinstance(s, scipy.integrate.Radau) and s.t == t and s.status == "running" and jac == self._jac:
            s.y, s.f = np.array(y, dtype=float), self.fun(t, y)  # warm: see the module docstring
            s.current_jac = False
            return
        self._jac = jac
        if isinstance(self.solver, FixedStep):
            self.solver.reset(t, y)
        elif o.method in FIXED_ONLY:
            extra = {"npos": o.npos} if o.method in SECOND_ORDER else {}
            self.solver = METHODS[o.method](self.fun, t, y, self.t_end, max_step=o.dt, **extra)
        elif o.dt is None:
            self.solver = METHODS[o.method](
                self.fun, t, y, self.t_end, first_step=first, max_step=o.max_step, rtol=o.rtol, atol=o.atol, **extra
            )
        else:
            self.solver = METHODS[o.method](
                self.fun, t, y, self.t_end, first_step=first, max_step=o.dt, rtol=1.0, atol=FIXED_ATOL, **extra
            )

    def step(self) -> tuple[float, np.ndarray]:
        """One accepted step: (t, y) at its end.

        Raises:
            IntegrationFailed: the step size fell below scipy's smallest.
        """
        s = self.solver
        t0 = s.t
        with np.errstate(under="ignore"):  # scipy's smallest step at t = 0 is a subnormal number
            message = s.step()
        if s.status == "failed":
            raise IntegrationFailed(t0, str(message))
        self.h = s.t - t0 if self.options.dt is None else self.options.dt
        if self.options.dt is None and getattr(s, "h_abs", None):
            self.h = float(s.h_abs)  # the size the controller chose for the next step
        return s.t, s.y.copy()

    def dense(self) -> Callable[[float], np.ndarray]:
        """The last step's dense output (callable on [t0, t1])."""
        return self.solver.dense_output()


def first_crossing(
    events: Sequence[Event], dense: Callable[[float], np.ndarray], t0: float, y0: np.ndarray, t1: float, y1: np.ndarray
) -> tuple[int, float] | None:
    """The earliest event crossing in a step, located by Brent's method on the step's dense output.

    Args:
        events: the events.
        dense: the step's dense output, t -> y on [t0, t1].
        t0: the step's start (s).
        y0: the state there.
        t1: the step's end (s).
        y1: the state there.

    Returns:
        (index into `events`, crossing time (s)) of the earliest crossing on (t0, t1] in an event's
        direction, or None.
    """
    best = None
    for k, ev in enumerate(events):
        g0, g1 = ev.fn(t0, y0), ev.fn(t1, y1)
        rising, falling = g0 < 0 <= g1, g0 > 0 >= g1
        if not ((ev.direction >= 0 and rising) or (ev.direction <= 0 and falling)):
            continue
        if g1 == 0.0:
            te = t1
        else:
            te = scipy.optimize.brentq(lambda s, fn=ev.fn: fn(s, dense(s)), t0, t1, xtol=EVENT_XTOL)
        if best is None or te < best[1]:
            best = (k, te)
    return best


def run(
    fun: Function,
    t0: float,
    y0: np.ndarray,
    t_end: float,
    options: Options,
    project: Callable[[float, np.ndarray], np.ndarray] | None = None,
) -> tuple[list[float], list[np.ndarray]]:
    """Every accepted step of dy/dt = fun(t, y) from (t0, y0) to t_end, each followed by `project` (no events).

    The simulator's own loop (`mechkit.simulation.simulate`) adds events; this one serves equations of
    motion written outside it (the ten-bar's Lagrange model, integrated by the same method as its
    Pinocchio route).

    Args:
        fun: dy/dt = fun(t, y).
        t0: the initial time (s).
        y0: the initial state.
        t_end: the end time (s).
        options: how to step.
        project: (t, y) -> y put back on the constraint manifold after each step, or None.

    Returns:
        The times (s) and the states of every accepted step, the initial ones first (y0 projected).

    Raises:
        IntegrationFailed: the step size collapsed.
    """
    y = project(t0, y0) if project is not None else np.array(y0, dtype=float)
    times, states = [t0], [y]
    stepper = Stepper(fun, t_end, options)
    t = t0
    while t < t_end - 1e-12 * max(1.0, abs(t_end)):
        stepper.restart(t, y)
        t, y = stepper.step()
        if project is not None:
            y = project(t, y)
        times.append(t)
        states.append(y)
    return times, states
