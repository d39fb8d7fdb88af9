"""Parameters of one 3RR-3URU tetrahedral unit (Xu et al. 2017, references/003, section 3.2).

`TetraParams` is the parameter set of the unit `tetra_3rr3uru`; the composite `deployable_9rr12uru`
extends it with its constraint chains. Zero joint coordinates of the models are the reference
configuration (alpha_ref, gamma_ref): the paper's drive laws at t = 0 of the fold.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.params import MechanismParams, param
from mechkit.mechanisms.truss.drives import drive_state
from mechkit.mechanisms.truss.geometry import TrussGeometry, half_angle_beta

_T0 = drive_state(0.0)


@dataclass(frozen=True)
class TetraParams(MechanismParams):
    """Rod lengths (m), reference fold angles (rad) and masses (kg) of the tetrahedral unit."""

    L: float = param(0.590, "m", "web rod length AH = BH = EH (Adams model, section 3.2)")
    l1: float = param(0.2504, "m", "each link of the folding rods AB, AE")
    l2: float = param(0.250, "m", "each link of the folding rod BE")
    alpha_ref: float = param(
        _T0.alpha, "rad", "fold angle of the reference configuration: the drive law at t = 0", positive=True
    )
    gamma_ref: float = param(_T0.gamma, "rad", "tilt of the reference configuration: the drive law at t = 0 (= gamma0)")
    node_mass: float = param(0.20, "kg", "node hub (aluminium, about 60 mm across)", ours=True)
    web_mass: float = param(0.12, "kg", "web rod (CFRP tube, 0.2 kg/m)", ours=True)
    link_mass: float = param(0.05, "kg", "one link of a folding rod (CFRP tube, 0.2 kg/m)", ours=True)
    cross_mass: float = param(0.01, "kg", "Hooke-joint cross", ours=True)
    tube_outer: float = param(0.020, "m", "outer diameter of the rods' CFRP tube (elastic section)", ours=True)
    tube_inner: float = param(0.016, "m", "inner diameter of the rods' CFRP tube (elastic section)", ours=True)
    rod_masses: str = param(
        "given",
        "-",
        "rods' masses: given (web_mass, link_mass) or from the tube (1600 kg/m^3 x "
        "area x length), for design studies of the section",
        ours=True,
    )

    def validate(self) -> None:
        """The folding rods can reach at the reference fold angle, in (0, 90) deg.

        Raises:
            InvalidParameters: one of them fails.
        """
        half_angle_beta(self.l1, self.l2)
        if not 0.0 <= self.tube_inner < self.tube_outer:
            raise InvalidParameters("tube_inner", self.tube_inner, f"must lie in [0, tube_outer = {self.tube_outer}) m")
        if self.rod_masses not in ("given", "tubes"):
            raise InvalidParameters("rod_masses", self.rod_masses, "one of given, tubes")
        if not 0.0 < self.alpha_ref < np.pi / 2:
            raise InvalidParameters("alpha_ref", self.alpha_ref, "the fold angle must lie in (0, 90) deg")
        geometry = self.geometry()
        local = geometry.unit_local(self.alpha_ref)
        for rod, (a, b), link in (
            ("AB", ("A", "B"), self.l1),
            ("AE", ("A", "E"), self.l1),
            ("BE", ("B", "E"), self.l2),
        ):
            chord = float(np.linalg.norm(local[b] - local[a]))
            if chord >= 2.0 * link:
                raise InvalidParameters(
                    "alpha_ref",
                    self.alpha_ref,
                    f"folding rod {rod} cannot reach: chord {chord:.4f} m >= 2 x link {2 * link:.4f} m",
                )

    def geometry(self) -> TrussGeometry:
        """The paper's analytic geometry at these dimensions."""
        return TrussGeometry(self.L, self.l1, self.l2)
