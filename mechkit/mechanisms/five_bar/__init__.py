"""Planar five-bar: the 2-DOF calibration mechanism of the core (not from the references).

Plane x-z (z up), revolute axes along -y. Proximal joints prox1 at A1 = origin and prox2 at
A2 = (ground, 0, 0), both actuated (absolute angles); distal joints dist1, dist2 (relative angles);
the loop is cut at the distal pin C, assembled on the branch with C above the line B1B2.

Modules: `params` (dimensions), `closed_form` (the exact motion of `mechkit.validation`, from which
the shared `mechkit.mechanisms.planar_linkage` builds the bench methods and references), `failure`
(the failure atlas's study of the singular pose where the distal bars are collinear).
"""

from __future__ import annotations

from mechkit.catalog.contract import MechanismSpec
from mechkit.mechanisms.five_bar.closed_form import motion
from mechkit.mechanisms.five_bar.failure import FAILURE_STUDIES
from mechkit.mechanisms.five_bar.params import FiveBarParams
from mechkit.mechanisms.planar_linkage.bench import bench_methods, bench_references

SPEC = MechanismSpec(
    name="five_bar",
    params=FiveBarParams,
    template="five_bar.urdf.xacro",
    actuated=("prox1", "prox2"),
    gruebler_dof=2,
    home=lambda p: {"prox1": 2.0, "prox2": 1.1},
    guess=lambda p: {"dist1": -1.2, "dist2": 1.0},
    summary="planar five-bar, 2-DOF calibration mechanism of the core",
    caption="Planar five-bar, two cranks driven (calibration mechanism)",
    bench_methods=bench_methods(motion),
    bench_references=bench_references(motion),
    failure_studies=FAILURE_STUDIES,
)

__all__ = ["SPEC", "FiveBarParams"]
