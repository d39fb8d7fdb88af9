"""Spatial 2T1R parallel mechanism with a redundant limb (Huang, Shen, Li, Zhu, Yang; reference 001).

A five-bar limb (I) and two RRR limbs (II, III) carry a platform; every joint axis is along y, so the
platform translates in x-z and turns about y. Actuation: R11, R21, R31 (theta_1..theta_3); with
``redundant_actuation=True`` R41 (theta_4) is driven too (four motors for three degrees of freedom,
minimum-norm torques in the validators).

Modules (each imports only the core, `mechkit.validation` and the siblings listed before it):
`kinematics` (the paper's position analysis: FK, IK), `rates` (velocities and accelerations, body
motion), `assembly` (the example inputs and the assembled branch), `params` (parameters, mass
properties, motors), `motion_law` (the paper's law, analytic states), `joint_state` (analytic state
-> URDF joint coordinates), `soc` (SKC decomposition, classic virtual work), `compare` (the three
inverse dynamics methods), `studies` (the comparison along the motion law and the singular studies,
as data), `figures` (drawn from them), `checks` (report rows), `scenes`, `bench` (`mechkit bench`
methods and reference).
"""

from __future__ import annotations

from mechkit.catalog.contract import MechanismSpec, MechanismStudy, MotionLaw
from mechkit.mechanisms.parallel_2t1r import bench, figures, studies
from mechkit.mechanisms.parallel_2t1r.branch import EXAMPLE_INPUTS, INPUTS, assembled_pose
from mechkit.mechanisms.parallel_2t1r.checks import self_checks
from mechkit.mechanisms.parallel_2t1r.joint_state import joint_positions
from mechkit.mechanisms.parallel_2t1r.motion_law import sampled_motion_law
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams, actuated
from mechkit.mechanisms.parallel_2t1r.rates import at_rest
from mechkit.mechanisms.parallel_2t1r.scenes import motion_law_scene, motion_law_times


def _guess(p: Parallel2T1RParams) -> dict[str, float]:
    pose, theta4, _ = assembled_pose(p.dims, EXAMPLE_INPUTS)
    return joint_positions(p, at_rest(pose, EXAMPLE_INPUTS, theta4))


def _home(p: Parallel2T1RParams) -> dict[str, float]:
    home = dict(zip(INPUTS, EXAMPLE_INPUTS))
    if p.redundant_actuation:
        home["R41"] = _guess(p)["R41"]
    return home


SPEC = MechanismSpec(
    name="parallel_2t1r",
    params=Parallel2T1RParams,
    template="parallel_2t1r.urdf.xacro",
    actuated=actuated,
    gruebler_dof=3,
    home=_home,
    guess=_guess,
    summary="spatial 2T1R parallel mechanism, five-bar limb + 2 RRR limbs, all axes along y (ref. 001)",
    caption="2T1R parallel mechanism: five-bar limb and two RRR limbs carrying the platform",
    scenes={"motion_law": motion_law_scene},
    scene_times={"motion_law": motion_law_times},
    scene_captions={"motion_law": "the paper's 5 s motion law, start (faded) to end (solid)"},
    view=(0.35, -1.0, 0.45),  # the motion is in the x-z plane: seen from -y, slightly above
    bench_methods=bench.METHODS,
    bench_references=bench.REFERENCES,
    motion_laws={"motion_law": MotionLaw(sampled_motion_law, reactions=("R13", "R23", "R43"))},
    studies={
        "comparison": MechanismStudy(
            "SOC vs Pinocchio vs classic virtual work along the paper's motion law",
            studies.comparison,
            studies.comparison_lines,
            figures.comparison_figure,
        ),
        "singular": MechanismStudy(
            "the motion law's singular start; theta_1 driven onto theta_2, plain vs redundant actuation",
            studies.singular,
            studies.singular_lines,
            figures.singular_figure,
        ),
    },
    self_checks=self_checks,
)

__all__ = ["SPEC", "Parallel2T1RParams"]
