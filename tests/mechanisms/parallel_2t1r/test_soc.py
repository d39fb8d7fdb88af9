"""`mechkit.mechanisms.parallel_2t1r.soc`: the SKC order and unknowns, SOC against classic virtual work."""

from __future__ import annotations

import pytest

from mechkit.base.exceptions import SingularConfiguration
from mechkit.mechanisms.parallel_2t1r.motion_law import motion_law, state_at
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams
from mechkit.mechanisms.parallel_2t1r.soc import classic_torques, skcs, soc_inverse_dynamics


def test_soc_equals_classic_virtual_work_at_one_instant():
    """Two virtual-work routes on the same loads: SKC by SKC, and the whole mechanism at once."""
    p = Parallel2T1RParams()
    s = state_at(p, *motion_law(2.2))
    soc = soc_inverse_dynamics(p, s)
    ours, _ = classic_torques(p, s)
    assert soc.consistency["SKC1"] < 1e-12
    for joint in ("R11", "R21", "R31"):
        assert soc.efforts[joint] == pytest.approx(ours[joint], rel=1e-10)


def test_skc_order_and_unknowns():
    p = Parallel2T1RParams()
    s = state_at(p, *motion_law(1.0))
    names = [
        (k.name, [a for a, _ in k.actuators], [r.joint for r in k.released], [r.joint for r in k.known])
        for k in skcs(p, s)
    ]
    assert names == [
        ("SKC3", [], ["R43"], []),
        ("SKC2", ["R31"], ["R23"], ["R43"]),
        ("SKC1", ["R11", "R21"], [], ["R23"]),
    ]
    with pytest.raises(SingularConfiguration):
        classic_torques(p, s, ("R11", "R21"))  # two motors cannot hold three DOF
