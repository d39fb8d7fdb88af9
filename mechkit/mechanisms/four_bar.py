"""Planar four-bar: the calibration mechanism of the core (not from the references).

Plane x-z (z up), revolute axes along -y so positive angles turn +x towards +z. Crank A at the
origin (actuated, absolute angle), coupler on the crank tip (relative angle), rocker pivot D at
(ground, 0, 0) (absolute angle). The loop is cut at the coupler-rocker pin C. Dimensions form a
Grashof crank-rocker (0.10 + 0.30 <= 0.28 + 0.22) so the crank turns fully.
"""

from __future__ import annotations

from dataclasses import dataclass

from mechkit.exceptions import InvalidParameters
from mechkit.params import MechanismParams, param
from mechkit.contract import MechanismSpec


@dataclass(frozen=True)
class FourBarParams(MechanismParams):
    ground: float = param(0.30, "m", "distance between the fixed pivots A and D", ours=True)
    crank: float = param(0.10, "m", "crank length AB", ours=True)
    coupler: float = param(0.28, "m", "coupler length BC", ours=True)
    rocker: float = param(0.22, "m", "rocker length DC", ours=True)
    width: float = param(0.02, "m", "bar width, in the plane", ours=True)
    thickness: float = param(0.01, "m", "bar thickness, along the axes", ours=True)
    density: float = param(2700.0, "kg/m^3", "aluminium", ours=True)
    rows: str = param("planar", "-", "closure rows: planar (2 per pin) or spatial (5 per pin)")

    def validate(self) -> None:
        lengths = [self.ground, self.crank, self.coupler, self.rocker]
        if max(lengths) >= sum(lengths) - max(lengths):
            raise InvalidParameters("ground/crank/coupler/rocker", lengths,
                                    "the longest link must be shorter than the sum of the others, or the loop cannot close")


SPEC = MechanismSpec(
    name="four_bar",
    params=FourBarParams,
    template="four_bar.urdf.xacro",
    actuated=("crank",),
    gruebler_dof=1,
    home=lambda p: {"crank": 0.6},
    guess=lambda p: {"coupler": 0.6, "rocker": 1.6},
    summary="planar four-bar (crank-rocker), calibration mechanism of the core",
)
