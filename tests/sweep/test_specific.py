"""`mechkit.sweep.specific`: the metrics a mechanism declares, read from its spec."""

from __future__ import annotations


def test_deployment_metric_through_the_sweep(load_cached):
    """The sweep reads the ten-bar's `deployment` metric from its spec: the largest motor torque of the
    deployment at the scene's step (R1, about 86 N m at 5 ms) and a latch speed."""
    from mechkit.sweep.specific import resolve

    metrics = {m.name: m for m in resolve("ten_bar", None)}
    assert list(metrics) == ["assembles", "branch", "deployment"]
    mech = load_cached("ten_bar")
    values = metrics["deployment"].fn(mech, None)
    assert set(values) == set(metrics["deployment"].columns(mech)) == {"max_motor_torque", "latch_speed"}
    assert 80.0 < values["max_motor_torque"] < 95.0 and 0.0 <= values["latch_speed"] < 1.0
