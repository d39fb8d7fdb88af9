"""Planar five-bar: the 2-DOF calibration mechanism of the core (not from the references).

Plane x-z (z up), revolute axes along -y. Proximal joints prox1 at A1 = origin and prox2 at
A2 = (ground, 0, 0), both actuated (absolute angles); distal joints dist1, dist2 (relative angles);
the loop is cut at the distal pin C, assembled on the branch with C above the line B1B2.
"""

from __future__ import annotations

from dataclasses import dataclass

from mechkit.params import MechanismParams, param
from mechkit.contract import MechanismSpec


@dataclass(frozen=True)
class FiveBarParams(MechanismParams):
    ground: float = param(0.25, "m", "distance between the fixed pivots A1 and A2", ours=True)
    prox1: float = param(0.12, "m", "proximal link 1, A1B1", ours=True)
    dist1: float = param(0.22, "m", "distal link 1, B1C", ours=True)
    prox2: float = param(0.12, "m", "proximal link 2, A2B2", ours=True)
    dist2: float = param(0.22, "m", "distal link 2, B2C", ours=True)
    width: float = param(0.02, "m", "bar width, in the plane", ours=True)
    thickness: float = param(0.01, "m", "bar thickness, along the axes", ours=True)
    density: float = param(2700.0, "kg/m^3", "aluminium", ours=True)
    rows: str = param("planar", "-", "closure rows: planar (2 per pin) or spatial (5 per pin)")


SPEC = MechanismSpec(
    name="five_bar",
    params=FiveBarParams,
    template="five_bar.urdf.xacro",
    actuated=("prox1", "prox2"),
    gruebler_dof=2,
    home=lambda p: {"prox1": 2.0, "prox2": 1.1},
    guess=lambda p: {"dist1": -1.2, "dist2": 1.0},
    summary="planar five-bar, 2-DOF calibration mechanism of the core",
)
