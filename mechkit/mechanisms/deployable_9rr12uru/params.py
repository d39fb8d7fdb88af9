"""Parameters of the 9RR-12URU composite: the unit's (`truss.params.TetraParams`) plus its chains."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.params import param
from mechkit.mechanisms.truss.params import TetraParams


@dataclass(frozen=True)
class DeployableParams(TetraParams):
    """The tetrahedral unit's parameters plus the links of the three URU constraint chains (m)."""

    l3: float = param(0.250, "m", "each link of the constraint chains EC, DF, BG (paper silent; = l2)", ours=True)

    def validate(self) -> None:
        """The unit's checks, and each constraint chain EC, DF, BG must reach: chord < 2 l3.

        Raises:
            InvalidParameters: a chain cannot close at the reference fold.
        """
        super().validate()
        nodes = self.geometry().node_positions(self.alpha_ref, self.gamma_ref)
        for chain in ("EC", "DF", "BG"):
            chord = float(np.linalg.norm(nodes[chain[1]] - nodes[chain[0]]))
            if chord >= 2.0 * self.l3:
                raise InvalidParameters("l3", self.l3, f"chain {chain} cannot reach: chord {chord:.4f} m >= 2 l3")
