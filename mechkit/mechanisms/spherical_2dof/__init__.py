"""2-DOF spherical parallel platform for low-frequency vibration isolation (Zhang et al. 2016).

A platform on a central strut through a Hooke joint at O, driven by two RRR limbs whose axes all
pass through O (every point moves on a sphere about O). Motors at the base joints r11, r21.

Modules, bottom up: `kinematics` (the paper's eqs. 4-12, numpy only), `params`, `joint_state` (the
Pinocchio tree filled from the paper's kinematics), `scenes` (the cone scene), `fk` (forward
kinematics three ways: the paper's iteration, Newton, the core's closure solver; and their basins),
`soc` (the SOC decomposition), `checks` (`mechkit report` rows), `bench` (`mechkit bench` methods),
`studies` (the cone scene as the paper's Figs. 5-7 with its dynamics, the FK's basins, as data) and
`figures` (drawn from them). Conventions the source leaves out (roll/pitch, platform-side axes, the
reading of "cone angle 30 deg") are derived in docs/mechanisms/spherical_2dof.md.
"""

from __future__ import annotations

from mechkit.catalog.contract import MechanismSpec, MechanismStudy
from mechkit.mechanisms.spherical_2dof import bench, checks, figures, joint_state, scenes, studies
from mechkit.mechanisms.spherical_2dof.params import Spherical2DofParams
from mechkit.mechanisms.spherical_2dof.scenes import cone_scene, cone_scene_times

__all__ = ["SPEC", "Spherical2DofParams"]

SPEC = MechanismSpec(
    name="spherical_2dof",
    params=Spherical2DofParams,
    template="spherical_2dof.urdf.xacro",
    actuated=("r11", "r21"),
    gruebler_dof=2,
    home=joint_state.home,
    guess=joint_state.guess,
    summary="2-DOF spherical parallel platform (2 RRR limbs + central Hooke strut), vibration isolation",
    caption="2-DOF spherical platform: two RRR limbs and a central Hooke strut",
    scenes={"cone": cone_scene},
    scene_times={"cone": cone_scene_times},
    scene_captions={"cone": "one turn of the platform's cone (solid: its start, faded: later phases)"},
    bench_methods=bench.METHODS,
    bench_references=bench.REFERENCES,
    studies={
        "cone": MechanismStudy(
            "the cone scene: the paper's Figs. 5-7, plus its dynamics by two methods",
            studies.cone,
            studies.cone_lines,
            figures.cone_figure,
        ),
        "basin": MechanismStudy(
            "where the forward kinematics fails: convergence basins of three methods",
            studies.basin,
            studies.basin_lines,
            figures.basin_figure,
        ),
        "ship": MechanismStudy(
            "on a ship (mechkit.bases): the inputs holding the platform level, torques, the carrier's force",
            scenes.ship_study,
            scenes.ship_lines,
            scenes.ship_figures,
        ),
        "isolation": MechanismStudy(
            "the isolation chart: residual tilt over carrier tilt against frequency, 1 and 4 Hz servos",
            scenes.isolation_study,
            scenes.isolation_lines,
            scenes.isolation_figures,
        ),
    },
    self_checks=checks.self_checks,
)
