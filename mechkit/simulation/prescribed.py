"""Prescribed joints of a simulation: inputs following a motion law (computed-torque motors) and joints
held at a value (a latch that has caught, a joint stopped at its limit).

A `Drives` gives, at time t, the positions (rad or m), rates and accelerations of its joints in its
order; the simulator keeps those joints on them (their accelerations in the dynamics, their values
and rates in the projection) and records the efforts that do it.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.interpolate

from mechkit.base.exceptions import InvalidParameters

Law = Callable[[float], tuple[np.ndarray, np.ndarray, np.ndarray]]
"""t (s) -> (positions (k,), rates (k,), accelerations (k,)) of the law's joints."""


def law_of_samples(law: Any) -> Law:
    """The continuous law through a sampled input law: a piecewise quintic matching values, rates and
    accelerations at every sample (`scipy.interpolate.BPoly.from_derivatives`, joined into one piecewise
    polynomial of every joint: one evaluation a time for all of them).

    Args:
        law: the sampled law (`mechkit.motion.InputLaw`: names, t (N,), values, rates and accelerations
            (N, k)).

    Returns:
        The `Law`, t (s) -> (positions, rates, accelerations) (k,); outside the sampled span the end
        values, at rest.
    """
    t = np.asarray(law.t, dtype=float)
    pieces = [
        scipy.interpolate.BPoly.from_derivatives(
            t, np.stack([law.values[:, k], law.rates[:, k], law.accelerations[:, k]], axis=1)
        )
        for k in range(len(law.names))
    ]
    joined = scipy.interpolate.BPoly(np.stack([p.c for p in pieces], axis=-1), pieces[0].x)  # every joint at once
    coefficients = [np.ascontiguousarray(d.c) for d in (joined, joined.derivative(), joined.derivative(2))]
    breaks = joined.x.tolist()
    last: list = [None, None]  # the last time asked and its answer (a step asks for it several times)

    def at(time: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        if time < t[0] or time > t[-1]:
            edge = 0 if time < t[0] else -1
            return law.values[edge].copy(), np.zeros(len(pieces)), np.zeros(len(pieces))
        if time in (t[0], t[-1]):  # the end samples as given (their rates and accelerations, not rest)
            edge = 0 if time == t[0] else -1
            return law.values[edge].copy(), law.rates[edge].copy(), law.accelerations[edge].copy()
        if last[0] != time:
            last[:] = time, tuple(_bernstein(c, breaks, time) for c in coefficients)
        return tuple(x.copy() for x in last[1])

    return at


def _bernstein(c: np.ndarray, x: list[float], time: float) -> np.ndarray:
    """A piecewise polynomial in the Bernstein basis (scipy's `BPoly` coefficients c (degree + 1, pieces, k) on
    breakpoints x) at one time inside [x[0], x[-1]]: sum_j c_j C(n, j) s^j (1 - s)^(n - j) on its piece (scipy's
    own call costs about 40 us: most of a step's time on the ten-bar's deployment)."""
    i = min(max(bisect.bisect_right(x, time) - 1, 0), len(x) - 2)
    s = (time - x[i]) / (x[i + 1] - x[i])
    n = len(c) - 1
    weights = [math.comb(n, j) * s**j * (1.0 - s) ** (n - j) for j in range(n + 1)]
    return np.dot(weights, c[:, i, :])


@dataclass
class Drives:
    """The joints the simulator keeps on a law: prescribed inputs (a law of time) and held joints.

    Attributes:
        names: the prescribed joints, in the law's order.
        law: their law (`Law`), or None without prescribed joints.
        held: joint -> value (rad or m) of the joints held still (latched, stopped at a limit).
    """

    names: tuple[str, ...] = ()
    law: Law | None = None
    held: dict[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if bool(self.names) != (self.law is not None):
            raise InvalidParameters("drives", self.names, "prescribed joints need a law, and a law its joints")

    @property
    def all(self) -> tuple[str, ...]:
        """Every driven joint: the prescribed ones, then the held ones."""
        return self.names + tuple(self.held)

    def at(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The driven joints' law at a time.

        Args:
            t: the time (s).

        Returns:
            Positions (rad or m), rates and accelerations (k,) of every driven joint, in `all` order
            (the held joints at rest).
        """
        k = len(self.held)
        if self.law is None:
            return np.array(list(self.held.values()), dtype=float), np.zeros(k), np.zeros(k)
        pos, rate, acc = (np.atleast_1d(np.asarray(x, dtype=float)) for x in self.law(t))
        hold = np.array(list(self.held.values()), dtype=float)
        return np.concatenate([pos, hold]), np.concatenate([rate, np.zeros(k)]), np.concatenate([acc, np.zeros(k)])

    def holding(self, joint: str, value: float) -> Drives:
        """These drives with one more joint held.

        Args:
            joint: the joint to hold.
            value: where it is held (rad or m).

        Returns:
            The new `Drives`.
        """
        return Drives(self.names, self.law, {**self.held, joint: float(value)})

    def releasing(self, joint: str) -> Drives:
        """These drives without holding a joint.

        Args:
            joint: the joint to release.

        Returns:
            The new `Drives`.
        """
        return Drives(self.names, self.law, {j: x for j, x in self.held.items() if j != joint})


def prescribed(inputs: Any, names: Sequence[str] | None = None) -> Drives:
    """Drives from what a user gives.

    Args:
        inputs: None (no prescribed joint), a sampled input law (`mechkit.motion.InputLaw`), a `Law`
            callable, or a mapping joint -> constant value (rad or m) held still.
        names: the joints of a `Law` callable, in its order.

    Returns:
        The `Drives`.

    Raises:
        InvalidParameters: a callable without names, or an input of another kind.
    """
    if inputs is None:
        return Drives()
    if isinstance(inputs, Mapping):
        return Drives(held={str(j): float(x) for j, x in inputs.items()})
    if callable(inputs):
        if not names:
            raise InvalidParameters("input_names", names, "a law given as a function needs the names of its joints")
        return Drives(tuple(names), inputs)
    if all(hasattr(inputs, a) for a in ("names", "t", "values", "rates", "accelerations")):
        return Drives(tuple(inputs.names), law_of_samples(inputs))
    raise InvalidParameters(
        "inputs",
        type(inputs).__name__,
        "expected an InputLaw, a function of time with input_names, or a mapping joint -> value",
    )
