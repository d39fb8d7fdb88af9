"""Two-way swinging mechanism of a launcher engine (Qian, Fu, Zhang, Zhu; reference 004).

The engine turns about a fixed point O: gimbal frame -> bracket about Ox1, bracket -> engine about
Oy2 (hinges at 45 deg to Ox / Oy, meeting at O). Two U-P-S actuators A and B drive it; their strokes
are the inputs. Frames: the paper frame O-xyz (z along the nozzle) is the URDF link `gimbal_frame`;
it hangs nozzle-down from the world (`rocket`, z up): world = Rx(pi) * paper.

Modules, bottom up: `kinematics` (the paper's IK, Newton FK, pitch / yaw, the linear rule, numpy
only), `resultant` (the paper's FK: half-angle substitution, Sylvester resultant, common-root test),
`body_motion` (every body's motion from (alpha, beta)), `params` (parameters, pivots, inertias),
`joint_state` (the Pinocchio tree from the motion), `scenes` (the swing under thrust), `soc` (the SKC
decomposition), `checks` (`mechkit report` rows), `bench` (`mechkit bench` methods), `failure` (the
failure atlas's study of the resultant's lost digits), `design` (the sweep's `rule_error`),
`studies` (the linear rule's error map, the resultant's conditioning, the swing by two methods, as
data) and `figures` (drawn from them).

Not in the source (ours): the pivot coordinates (a reconstruction that reproduces the paper's
printed numbers), every mass and inertia, the actuator dimensions.
"""

from __future__ import annotations

from mechkit.catalog.contract import MechanismSpec, MechanismStudy
from mechkit.mechanisms.rocket_gimbal import bench, checks, figures, scenes, studies
from mechkit.mechanisms.rocket_gimbal.design import DESIGN_METRICS
from mechkit.mechanisms.rocket_gimbal.failure import FAILURE_STUDIES
from mechkit.mechanisms.rocket_gimbal.params import RocketGimbalParams, geometry
from mechkit.mechanisms.rocket_gimbal.scenes import swing_scene, swing_times

__all__ = ["SPEC", "RocketGimbalParams"]

SPEC = MechanismSpec(
    name="rocket_gimbal",
    params=RocketGimbalParams,
    template="rocket_gimbal.urdf.xacro",
    actuated=("a_stroke", "b_stroke"),
    gruebler_dof=2,
    home=lambda p: {"a_stroke": 0.0, "b_stroke": 0.0},
    summary="launcher engine gimbal: frame-bracket-engine hinges at 45 deg, two U-P-S servo actuators",
    caption="Engine gimbal: bracket and engine hinges, two U-P-S servo actuators",
    scenes={"swing": swing_scene},
    scene_times={"swing": swing_times},
    scene_captions={"swing": "one period of the engine swing (solid: its start, faded: later phases)"},
    bench_methods=bench.METHODS,
    bench_references=bench.REFERENCES,
    failure_studies=FAILURE_STUDIES,
    design_metrics=DESIGN_METRICS,
    studies={
        "linearisation": MechanismStudy(
            "error map of the linear stroke-angle rule (110 mm <-> 6.5 deg)",
            lambda mech: studies.linearisation(geometry(mech.params)),
            studies.linearisation_lines,
            figures.linearisation_figure,
        ),
        "resultant": MechanismStudy(
            "conditioning of the resultant FK: the paper's example and a map over the strokes",
            lambda mech: studies.conditioning(geometry(mech.params)),
            studies.conditioning_lines,
            figures.conditioning_figure,
        ),
        "swing": MechanismStudy(
            "servo forces and support reactions over one period of the swing, Pinocchio vs SOC",
            studies.swing,
            studies.swing_lines,
            figures.swing_figure,
        ),
        "flight": MechanismStudy(
            "the swing on a vehicle accelerating at 2 g under 1.2 MN thrust (mechkit.bases) beside the bench",
            scenes.flight_study,
            scenes.flight_lines,
            scenes.flight_figures,
        ),
    },
    self_checks=checks.self_checks,
)
