"""Ten-bar under-actuated solar-array deployment linkage (patent CN105975733, Radarsat-2).

Topology (the patent's): the satellite side wall l1,5 holds R1 and R5; 9 moving links l1,2,3 (panel
1, with R10 welded on it), l3,4 (panel 2), l4,8, l8,7, l6,7, l5,6, l2,7, l7,9, l9,10; hinges R1..R10
with R7 a compound hinge of four links (three pairs), 12 revolute pairs, DOF = 3*9 - 2*12 = 3.
Loops: five-bar (wall, l123, l27, l67, l56; DOF 2), four-bar (l123, l27, l79, l910), six-bar
(l123, l34, l48, l87, l79, l910). Motors at R1 (panel 1 on the wall) and R3 (panel 2 on panel 1);
the third DOF, in the five-bar, is passive and driven by a torsion spring at R5, as the patent's
elastic elements drive the real hinges.

The patent gives no dimension. The design below is ours (parameters in `params`, geometry in
`geometry`):

- Panels: 1.2 m x 1.0 m rigid panels at 2.5 kg/m^2 (honeycomb substrate with cells, the usual
  2-3 kg/m^2), 3.0 kg each. Stowed (t = 0): panel 1 stands up along the wall (R1 angle pi/2),
  panel 2 folded back down on it (R3 angle -pi). Deployed: R1 = 0 and R3 = 0, l2,3 and l3,4
  collinear along +x, perpendicular to the wall.
- Every loop is sized with Grashof-type margins so that it closes for EVERY value of its inputs,
  not only along one planned path: the wall rocker R5-R6 (0.08 m) and the arm R1-R2 (0.117 m) are
  short against the wall gap (0.5 m), and |l67 - l27| = 0.25 < 0.5 - 0.117 - 0.08 while
  l67 + l27 = 0.75 > 0.5 + 0.117 + 0.08, so the five-bar closes for any (R1, R5); in panel 1's
  frame l27 (0.25) turns fully inside the four-bar (ground R2-R10 0.667, l79 + l910 = 1.13 >
  0.917, |l910 - l79| = 0.13 < 0.417); the dyad l48-l87 (0.9 + 0.9) spans every distance R4-R7
  can take (0.75..1.65 m). The passive DOF, which only the dynamics decides, can therefore never
  jam the linkage, and no loop meets a dead-centre pose: `Pose.margins` (sine of the angle at the
  closing hinge) stays >= 0.47 for every motor and rocker angle, >= 0.66 over the deployment.
- Branches: the three circle intersections take the side that keeps every hinge outside the wall
  (x > 0) over the deployment.
- Links: aluminium bars 25 mm x 10 mm (0.675 kg/m). The spring at R5 (4 N m/rad, 5.4 N m preload
  at the stowed angle, free angle +17.4 degrees, and a viscous damper as real deployment hinges
  carry) swings the rocker l56 from -60 degrees (stowed) within 0.2 s to about +2 degrees, where
  it balances the linkage's weight (about 1.2 N m on R5); it then follows the slowly changing
  balance (-4..+9 degrees) while the motors deploy the panels over 20 s. With 0.008-0.009 kg m^2
  of effective inertia on R5 its natural frequency (about 21 rad/s) sits well above the motor
  laws' and the damper (ratio about 0.8) keeps it from ringing.

Modules (each imports only the core, `mechkit.validation` and the siblings listed before it):
`params` (parameters, motor laws, spring), `geometry` (hinge layout, mass properties, closed-form
pose), `lagrange_model` (the patent's Lagrange model, numpy tree kinematics), `kinematics` (full
closure, the patent's dimension reduction), `soc` (SKC decomposition), `dynamics` (deployment: the
Pinocchio route through the simulator's equations, stepped with projection), `lagrange_deployment` (its
Lagrange route), `limits` (where the methods fail), `checks` (cross-checks, report rows), `scenes`
(the deployment as poses and as an input law), `bench` (`mechkit bench` methods and references),
`design` (the sweep's `deployment` metric), `studies` (the deployment's cross-checks and figures'
data) and `figures` (drawn from them).
"""

from __future__ import annotations

from mechkit.catalog.contract import MechanismSpec, MechanismStudy, MotionLaw
from mechkit.mechanisms.ten_bar import bench, figures, scenes, studies
from mechkit.mechanisms.ten_bar.checks import self_checks
from mechkit.mechanisms.ten_bar.design import DESIGN_METRICS
from mechkit.mechanisms.ten_bar.geometry import stowed_pose
from mechkit.mechanisms.ten_bar.params import MOTORS, PASSIVE, STOWED, TenBarParams
from mechkit.mechanisms.ten_bar.scenes import deployment_law, deployment_poses, deployment_times


def _home(p: TenBarParams) -> dict[str, float]:
    return {**STOWED, PASSIVE: p.stowed_rocker}


def _guess(p: TenBarParams) -> dict[str, float]:
    return stowed_pose(p).joint_angles()


SPEC = MechanismSpec(
    name="ten_bar",
    params=TenBarParams,
    template="ten_bar.urdf.xacro",
    actuated=MOTORS,
    gruebler_dof=3,
    home=_home,
    guess=_guess,
    summary="Radarsat-2 solar-array ten-bar (patent CN105975733): 9 links, 12 pairs, 2 motors + 1 spring DOF",
    caption="Radarsat-2 solar-array ten-bar: two motors and a spring-loaded DOF",
    scenes={"deploy": deployment_poses},
    scene_times={"deploy": deployment_times},
    scene_captions={"deploy": "the deployment, stowed (faded) to deployed (solid)"},
    bench_methods=bench.METHODS,
    bench_references=bench.REFERENCES,
    motion_laws={"deploy": MotionLaw(deployment_law, reactions=("R1", "R5", "R3"))},
    design_metrics=DESIGN_METRICS,
    studies={
        "cross_checks": MechanismStudy(
            "the deployment, stowed to deployed, by two dynamics routes, with every cross-check",
            studies.cross_checks,
            studies.cross_check_lines,
        ),
        "deployment": MechanismStudy(
            "deployment figures: linkage snapshots, joint angles, torques, wall supports, drift",
            studies.deployment,
            studies.deployment_lines,
            figures.deployment_figures,
        ),
        "orbit": MechanismStudy(
            "the deployment in orbit on a floating 100 kg bus (mechkit.bases) beside the ground test under 1 g",
            scenes.orbit_study,
            scenes.orbit_lines,
            scenes.orbit_figures,
        ),
    },
    self_checks=self_checks,
)

__all__ = ["SPEC", "TenBarParams"]
