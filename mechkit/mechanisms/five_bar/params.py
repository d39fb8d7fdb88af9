"""Parameters of the planar five-bar: link lengths, bar section and material, closure rows."""

from __future__ import annotations

from dataclasses import dataclass

from mechkit.catalog.params import MechanismParams, param


@dataclass(frozen=True)
class FiveBarParams(MechanismParams):
    """Five-bar dimensions (m), bar section and material, closure rows; pivots A1 and A2 on the x axis."""

    ground: float = param(0.25, "m", "distance between the fixed pivots A1 and A2", ours=True)
    prox1: float = param(0.12, "m", "proximal link 1, A1B1", ours=True)
    dist1: float = param(0.22, "m", "distal link 1, B1C", ours=True)
    prox2: float = param(0.12, "m", "proximal link 2, A2B2", ours=True)
    dist2: float = param(0.22, "m", "distal link 2, B2C", ours=True)
    width: float = param(0.02, "m", "bar width, in the plane", ours=True)
    thickness: float = param(0.01, "m", "bar thickness, along the axes", ours=True)
    density: float = param(2700.0, "kg/m^3", "aluminium", ours=True)
    rows: str = param("planar", "-", "closure rows: planar (2 per pin) or spatial (5 per pin)")
