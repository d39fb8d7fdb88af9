"""Parameters of the planar four-bar: link lengths, bar section and material, closure rows."""

from __future__ import annotations

from dataclasses import dataclass

from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.params import MechanismParams, param


@dataclass(frozen=True)
class FourBarParams(MechanismParams):
    """Four-bar dimensions (m), bar section and material, closure rows; pivots A and D on the x axis."""

    ground: float = param(0.30, "m", "distance between the fixed pivots A and D", ours=True)
    crank: float = param(0.10, "m", "crank length AB", ours=True)
    coupler: float = param(0.28, "m", "coupler length BC", ours=True)
    rocker: float = param(0.22, "m", "rocker length DC", ours=True)
    width: float = param(0.02, "m", "bar width, in the plane", ours=True)
    thickness: float = param(0.01, "m", "bar thickness, along the axes", ours=True)
    density: float = param(2700.0, "kg/m^3", "aluminium", ours=True)
    rows: str = param("planar", "-", "closure rows: planar (2 per pin) or spatial (5 per pin)")

    def validate(self) -> None:
        """The loop must close: the longest link shorter than the sum of the other three.

        Raises:
            InvalidParameters: it cannot.
        """
        lengths = [self.ground, self.crank, self.coupler, self.rocker]
        if max(lengths) >= sum(lengths) - max(lengths):
            raise InvalidParameters(
                "ground/crank/coupler/rocker",
                lengths,
                "the longest link must be shorter than the sum of the others, or the loop cannot close",
            )
