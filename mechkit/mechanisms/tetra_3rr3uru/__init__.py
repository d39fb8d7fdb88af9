"""The 3RR-3URU tetrahedral deployable unit H-ABE (Xu et al. 2017, references/003, Fig. 2), node A fixed.

Model (xacro/tetra_unit.xacro): 4 nodes, 3 web rods with a revolute at each end (axes normal to
the planes H-O1-X), 3 URU folding rods (two links, middle revolute, a Hooke joint at each node,
each Hooke as two revolutes with a small cross body). Each folding rod's loop is cut at its middle
revolute (5 spatial rows): 18 tree coordinates, 15 rows, 3 DOF (eq. 4). Zero joint coordinates are
the paper's configuration at t = 0 of the fold.

Drives: the paper's folding drive (web rod AH at node H) and attitude drive at B (rod BH at B),
and rod EH at H (`actuation.ACTUATED`). Shared with the composite (`mechkit.mechanisms.truss`): the
parameters, the drive laws, the web-joint motion, the fold, the bench's states along it. Own modules:
`soc` (SOC virtual work of the unit), `checks` (report rows), `bench` (`mechkit bench` methods and
reference). Scene: `fold` (the paper's 200 s fold).
"""

from __future__ import annotations

from mechkit.catalog.contract import MechanismSpec
from mechkit.mechanisms.tetra_3rr3uru import bench
from mechkit.mechanisms.tetra_3rr3uru.actuation import ACTUATED, home
from mechkit.mechanisms.tetra_3rr3uru.checks import self_checks
from mechkit.mechanisms.truss.bench import fold_states
from mechkit.mechanisms.truss.fold import fold_poses, fold_scene_times
from mechkit.mechanisms.truss.params import TetraParams

__all__ = ["SPEC", "TetraParams"]

SPEC = MechanismSpec(
    name="tetra_3rr3uru",
    params=TetraParams,
    template="tetra_3rr3uru.urdf.xacro",
    actuated=ACTUATED,
    gruebler_dof=3,
    home=home,
    summary="3RR-3URU tetrahedral deployable unit H-ABE of a truss antenna, node A fixed",
    caption="Tetrahedral 3RR-3URU deployable unit",
    scenes={"fold": fold_poses},
    scene_times={"fold": fold_scene_times},
    scene_captions={"fold": "the 200 s fold, deployed (faded) to folded (solid)"},
    bench_methods=bench.METHODS,
    bench_references=bench.REFERENCES,
    bench_states=fold_states,
    self_checks=self_checks,
)
