"""The 9RR-12URU deployable composite element (Xu et al. 2017, references/003, Fig. 1).

Three 3RR-3URU units H-ABE, J-AFC, I-ADG (as `tetra_3rr3uru`) share the fixed node A, turned by 0,
-120 and +120 deg about z (eq. 8), joined by the URU constraint chains EC, DF, BG: 43 bodies of the
paper plus 24 Hooke crosses, 66 tree coordinates, 12 cuts of 5 rows = 60 rows, rank 59 along the
paper's (three-fold symmetric) motions: 7 DOF with one redundant constraint (eq. 5); to second order
the seventh DOF holds only along those motions (`redundancy.second_order_form`). Drives (section
3.2): fold at H, J, I (web rods AH, AJ, AI), attitude at B, F, G (web rods BH, FJ, GI) and web rod
EH at H (`actuation.ACTUATED`); `truss.joint_state.web_joint_motion` gives their joint laws.

Shared with the unit (`mechkit.mechanisms.truss`): the drive laws, the web-joint motion, the fold
(`truss.fold`, closure solved along it by continuation; the `fold` scene), the node readings and
the fold checks (`truss.checks.fold_checks`, rows of `mechkit report`), the bench's states along the
fold and its continuation step (`truss.bench`). Own modules: `params` (the chain links),
`actuation`, `redundancy` (the self-stress, `mobility_without` with chains removed,
`indeterminate_direction` of the reactions, `second_order_form`), `studies` (the fold against the
paper's equations, as data) and `figures` (drawn from it).
"""

from __future__ import annotations

from mechkit.catalog.contract import MechanismSpec, MechanismStudy
from mechkit.mechanisms.deployable_9rr12uru import figures, orbit, studies
from mechkit.mechanisms.deployable_9rr12uru.actuation import ACTUATED, home
from mechkit.mechanisms.deployable_9rr12uru.params import DeployableParams
from mechkit.mechanisms.truss.bench import FOLD_STEP, fold_states
from mechkit.mechanisms.truss.checks import fold_checks
from mechkit.mechanisms.truss.fold import fold_poses, fold_scene_times

__all__ = ["SPEC", "DeployableParams"]

SPEC = MechanismSpec(
    name="deployable_9rr12uru",
    params=DeployableParams,
    template="deployable_9rr12uru.urdf.xacro",
    actuated=ACTUATED,
    gruebler_dof=7,
    home=home,
    summary="9RR-12URU deployable composite element of a truss antenna (3 tetrahedral units + 3 URU chains)",
    caption="9RR-12URU deployable mast of tetrahedral units",
    scenes={"fold": fold_poses},
    scene_times={"fold": fold_scene_times},
    scene_captions={"fold": "the 200 s fold, deployed (faded) to folded (solid)"},
    bench_methods=(FOLD_STEP,),
    bench_states=fold_states,
    studies={
        "fold": MechanismStudy(
            "the 200 s fold against the paper's eq. (6)-(13): Fig. 7-9, drives, torques",
            studies.fold_study,
            studies.fold_lines,
            figures.fold_figures,
        ),
        "orbit": MechanismStudy(
            "the 200 s fold in orbit on a floating 100 kg bus (mechkit.bases) beside the ground under 1 g (minutes)",
            orbit.orbit_study,
            orbit.orbit_lines,
            orbit.orbit_figures,
        ),
    },
    self_checks=fold_checks,
)
