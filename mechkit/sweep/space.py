"""The design space of a sweep: parameter axes and the designs drawn from them (grid, random, Latin hypercube).

An axis is written `name=lo:hi:n` (a grid of n values from lo to hi, both included) or `name=lo:hi`
(bounds only, for random and Latin-hypercube sampling). Every design has an index (its row key in
the results): grid designs in row-major order of the axes as given, sampled designs in draw order.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidParameters

MODES = ("grid", "random", "lhs")


@dataclass(frozen=True)
class Axis:
    """One swept parameter: bounds (its unit, SI) and the grid count (None: bounds only)."""

    name: str
    lo: float
    hi: float
    n: int | None = None

    def values(self) -> np.ndarray:
        """The grid values, lo to hi inclusive."""
        if self.n is None:
            raise InvalidParameters("grid", self.name, "a grid axis needs a count: name=lo:hi:n")
        return np.linspace(self.lo, self.hi, self.n)


def parse_axis(text: str) -> Axis:
    """`name=lo:hi:n` or `name=lo:hi` -> `Axis`.

    Args:
        text: the --grid argument.

    Returns:
        The axis (n None: for --random / --lhs).

    Raises:
        InvalidParameters: not of that form, bounds not finite or not increasing, n < 1.
    """
    name, sep, rest = text.partition("=")
    parts = rest.split(":")
    if not sep or not name.strip() or len(parts) not in (2, 3):
        raise InvalidParameters("grid", text, "expected name=lo:hi:n (or name=lo:hi with --random/--lhs)")
    try:
        lo, hi = float(parts[0]), float(parts[1])
        n = int(parts[2]) if len(parts) == 3 else None
    except ValueError:
        raise InvalidParameters("grid", text, "lo and hi must be numbers, n an integer") from None
    if not (math.isfinite(lo) and math.isfinite(hi)) or hi < lo:
        raise InvalidParameters("grid", text, "need finite bounds with lo <= hi")
    if n is not None and (n < 1 or (n > 1 and hi == lo)):
        raise InvalidParameters("grid", text, "n must be >= 1 (and 1 when lo == hi)")
    return Axis(name.strip(), lo, hi, n)


@dataclass(frozen=True)
class DesignSpace:
    """The axes and how designs are drawn from them.

    Attributes:
        axes: the swept parameters (names unique).
        mode: "grid" (every combination of the axes' values), "random" (uniform in the bounds) or
            "lhs" (Latin hypercube in the bounds).
        count: number of sampled designs (random, lhs); ignored for a grid.
        seed: seed of the random draws (numpy's default generator / scipy's LatinHypercube).
    """

    axes: tuple[Axis, ...]
    mode: str = "grid"
    count: int = 0
    seed: int = 0

    def __post_init__(self) -> None:
        if not self.axes:
            raise InvalidParameters("grid", (), "a sweep needs at least one axis (--grid name=lo:hi:n)")
        names = [a.name for a in self.axes]
        if len(set(names)) != len(names):
            raise InvalidParameters("grid", names, "each parameter may be swept once")
        if self.mode not in MODES:
            raise InvalidParameters("mode", self.mode, f"one of {', '.join(MODES)}")
        if self.mode == "grid":
            for axis in self.axes:
                axis.values()
        elif self.count < 1:
            raise InvalidParameters(self.mode, self.count, "the number of designs must be >= 1")

    @property
    def names(self) -> tuple[str, ...]:
        """The swept parameters' names, in axis order."""
        return tuple(a.name for a in self.axes)

    def designs(self) -> np.ndarray:
        """(designs, axes) parameter values; row i is the design of index i."""
        if self.mode == "grid":
            return np.array(list(itertools.product(*(a.values() for a in self.axes))), dtype=float)
        lo = np.array([a.lo for a in self.axes])
        hi = np.array([a.hi for a in self.axes])
        if self.mode == "random":
            unit = np.random.default_rng(self.seed).random((self.count, len(self.axes)))
        else:
            from scipy.stats import qmc

            unit = qmc.LatinHypercube(d=len(self.axes), seed=self.seed).random(self.count)
        return lo + unit * (hi - lo)

    def to_dict(self) -> dict:
        """A JSON-ready description (what a resumed sweep compares)."""
        return {
            "axes": [[a.name, a.lo, a.hi, a.n] for a in self.axes],
            "mode": self.mode,
            "count": self.count if self.mode != "grid" else 0,
            "seed": self.seed,
        }

    @classmethod
    def from_dict(cls, data: dict) -> DesignSpace:
        """The design space `to_dict` described.

        Args:
            data: the dict `to_dict` gave.

        Returns:
            The design space.
        """
        return cls(
            tuple(Axis(n, lo, hi, k) for n, lo, hi, k in data["axes"]), data["mode"], data["count"], data["seed"]
        )
