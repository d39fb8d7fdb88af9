"""`mechkit.mechanisms.ten_bar.kinematics`: each unit of the patent's dimension reduction has the patent's
mobility."""

from __future__ import annotations

import numpy as np

from mechkit import core
from mechkit.mechanisms.ten_bar import kinematics as tk


def test_each_unit_has_the_patents_mobility(mech):
    reduction = tk.DimensionReduction(mech)
    dof = {}
    for unit in reduction.units:
        q = np.array([mech.home_q[mech.q_index(j)] for j in unit.model.names[1:]])
        dof[unit.unit.name] = core.mobility(unit.closure_model, unit.closure_data, q).dof
    # five-bar 2 (the patent's), four-bar 1 on top of l123 (R2 given), six-bar 2 (R2 and the R3 motor)
    assert dof == {"five_bar": 2, "four_bar": 1, "six_bar": 2}
