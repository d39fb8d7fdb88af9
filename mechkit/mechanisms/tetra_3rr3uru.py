"""The 3RR-3URU tetrahedral deployable unit H-ABE (Xu et al. 2017, references/003, Fig. 2), node A fixed.

Model (xacro/tetra_unit.xacro): 4 nodes, 3 web rods with a revolute at each end (axes normal to
the planes H-O1-X), 3 URU folding rods (two links, middle revolute, a Hooke joint at each node,
each Hooke as two revolutes with a small cross body). Each folding rod's loop is cut at its middle
revolute (5 spatial rows): 18 tree coordinates, 15 rows, 3 DOF (eq. 4). Zero joint coordinates are
the paper's configuration at t = 0 of the fold.

Drives: the paper's folding drive (web rod AH at node H) and attitude drive at B (rod BH at B),
and rod EH at H (see `ACTUATED`). `web_joint_motion` gives every web joint along the paper's motion.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.exceptions import InvalidParameters
from mechkit.mechanisms.truss_geometry import (
    UNIT_NODES,
    DriveState,
    TrussGeometry,
    drive_state,
    half_angle_beta,
)
from mechkit.params import MechanismParams, param
from mechkit.contract import MechanismSpec

_T0 = drive_state(0.0)

#: Actuated joints of the unit: fold at H (paper), attitude at B (paper), and rod EH at H in place of
#: the paper's attitude drive at E: in this model the attitudes of B and E are tied to first order
#: at every configuration of the paper's motion (mirror symmetric), so B and E together cannot be
#: inputs (the passive block of the closure Jacobian is singular).
ACTUATED = ("AH_H", "BH_B", "EH_H")


@dataclass(frozen=True)
class TetraParams(MechanismParams):
    L: float = param(0.590, "m", "web rod length AH = BH = EH (Adams model, section 3.2)")
    l1: float = param(0.2504, "m", "each link of the folding rods AB, AE")
    l2: float = param(0.250, "m", "each link of the folding rod BE")
    alpha_ref: float = param(_T0.alpha, "rad", "fold angle of the reference configuration: the drive law at t = 0",
                             positive=True)
    gamma_ref: float = param(_T0.gamma, "rad", "tilt of the reference configuration: the drive law at t = 0 (= gamma0)")
    node_mass: float = param(0.20, "kg", "node hub (aluminium, about 60 mm across)", ours=True)
    web_mass: float = param(0.12, "kg", "web rod (CFRP tube, 0.2 kg/m)", ours=True)
    link_mass: float = param(0.05, "kg", "one link of a folding rod (CFRP tube, 0.2 kg/m)", ours=True)
    cross_mass: float = param(0.01, "kg", "Hooke-joint cross", ours=True)

    def validate(self) -> None:
        half_angle_beta(self.l1, self.l2)
        if not 0.0 < self.alpha_ref < np.pi / 2:
            raise InvalidParameters("alpha_ref", self.alpha_ref, "the fold angle must lie in (0, 90) deg")
        geometry = self.geometry()
        local = geometry.unit_local(self.alpha_ref)
        for rod, (a, b), link in (("AB", ("A", "B"), self.l1), ("AE", ("A", "E"), self.l1), ("BE", ("B", "E"), self.l2)):
            chord = float(np.linalg.norm(local[b] - local[a]))
            if chord >= 2.0 * link:
                raise InvalidParameters("alpha_ref", self.alpha_ref,
                                        f"folding rod {rod} cannot reach: chord {chord:.4f} m >= 2 x link {2 * link:.4f} m")

    def geometry(self) -> TrussGeometry:
        return TrussGeometry(self.L, self.l1, self.l2)


def web_joint_motion(p: TetraParams, s: DriveState, apexes: tuple[str, ...] = ("H",)) -> tuple[dict, dict, dict]:
    """Angles, rates, accelerations (rad, rad/s, rad/s^2) of every web-rod joint in the paper's motion s.

    Relative to the reference (alpha_ref, gamma_ref), per unit with apex X and nodes P, Q:
    rod AX at A turns by (gamma - gamma_ref) - (alpha - alpha_ref) (its absolute tilt), at X by
    alpha - alpha_ref (the fold drive); rods PX, QX turn by -(alpha - alpha_ref) at X and by
    (alpha - alpha_ref) - (gamma - gamma_ref) at P, Q (node attitude).
    """
    da = (s.alpha - p.alpha_ref, s.alpha_rate, s.alpha_acc)
    dg = (s.gamma - p.gamma_ref, s.gamma_rate, s.gamma_acc)
    out: tuple[dict, dict, dict] = ({}, {}, {})
    for apex in apexes:
        x, b, e = UNIT_NODES[apex]
        for k in range(3):
            out[k].update({f"A{x}_A": dg[k] - da[k], f"A{x}_{x}": da[k],
                           f"{b}{x}_{x}": -da[k], f"{b}{x}_{b}": da[k] - dg[k],
                           f"{e}{x}_{x}": -da[k], f"{e}{x}_{e}": da[k] - dg[k]})
    return out


def drive_inputs(p: TetraParams, s: DriveState, actuated: tuple[str, ...], apexes: tuple[str, ...]) -> tuple[dict, dict, dict]:
    """The paper's motion s on the actuated joints: (angles, rates, accelerations) by joint name."""
    motion = web_joint_motion(p, s, apexes)
    return tuple({joint: values[joint] for joint in actuated} for values in motion)


def _fold_poses(mech) -> list[np.ndarray]:
    from mechkit.mechanisms.deployable_9rr12uru import fold_poses

    return fold_poses(mech)


#: Animated scenes for `mechkit snapshot --scene` (scene name -> poses): the paper's 200 s fold.
SCENES = {"fold": _fold_poses}


def _self_checks(mech):
    from mechkit.mechanisms.deployable_9rr12uru import fold_checks

    return fold_checks(mech)


SPEC = MechanismSpec(
    name="tetra_3rr3uru",
    params=TetraParams,
    template="tetra_3rr3uru.urdf.xacro",
    actuated=ACTUATED,
    gruebler_dof=3,
    home=lambda p: {joint: 0.0 for joint in ACTUATED},
    summary="3RR-3URU tetrahedral deployable unit H-ABE of a truss antenna, node A fixed",
    self_checks=_self_checks,
)
