"""Planar four-bar: the calibration mechanism of the core (not from the references).

Plane x-z (z up), revolute axes along -y so positive angles turn +x towards +z. Crank A at the
origin (actuated, absolute angle), coupler on the crank tip (relative angle), rocker pivot D at
(ground, 0, 0) (absolute angle). The loop is cut at the coupler-rocker pin C. Dimensions form a
Grashof crank-rocker (0.10 + 0.30 <= 0.28 + 0.22) so the crank turns fully.

Modules: `params` (dimensions), `closed_form` (the exact motion of `mechkit.validation`, from which
the shared `mechkit.mechanisms.planar_linkage` builds the bench methods and references).
"""

from __future__ import annotations

from mechkit.catalog.contract import MechanismSpec
from mechkit.mechanisms.four_bar.closed_form import motion
from mechkit.mechanisms.four_bar.params import FourBarParams
from mechkit.mechanisms.planar_linkage.bench import bench_methods, bench_references

SPEC = MechanismSpec(
    name="four_bar",
    params=FourBarParams,
    template="four_bar.urdf.xacro",
    actuated=("crank",),
    gruebler_dof=1,
    home=lambda p: {"crank": 0.6},
    guess=lambda p: {"coupler": 0.6, "rocker": 1.6},
    summary="planar four-bar (crank-rocker), calibration mechanism of the core",
    caption="Planar four-bar crank-rocker (calibration mechanism)",
    bench_methods=bench_methods(motion),
    bench_references=bench_references(motion),
)

__all__ = ["SPEC", "FourBarParams"]
