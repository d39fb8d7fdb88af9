"""`mechkit.bench.work_precision`: on the four-bar, mechkit's error falls as its tolerance and step tighten,
the reference agrees with MuJoCo's RK4 at a fine step (an independent code) to MuJoCo's closure floor, on the
four-bar's export and on the Robotiq 2F-85's own file, and the verdict picks each code's cheapest run within the
bounds."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechkit.bench import work_precision as wp
from mechkit.simulation import DRIFT_TOL


@pytest.fixture(scope="module")
def four_bar(load_cached):
    return load_cached("four_bar")


@pytest.fixture(scope="module")
def q_end(four_bar):
    return wp.reference(four_bar, 0.3)


def test_mechkit_s_error_falls_as_its_tolerance_and_step_tighten(four_bar, q_end, monkeypatch):
    monkeypatch.setattr(wp, "MECHKIT_ADAPTIVE", (("DOP853", 1e-6), ("DOP853", 1e-10)))
    monkeypatch.setattr(wp, "MECHKIT_FIXED", (("RK4", 4e-3), ("RK4", 1e-3)))
    loose, tight, coarse, fine = wp.mechkit_points(four_bar, q_end, 0.3)
    assert tight.error < loose.error / 100 and fine.error < coarse.error / 100  # RK4: 4^4 = 256 expected
    # the simulator projects only past its drift tolerance (1e-11 m, below the 1e-10 m)
    assert max(p.closure for p in (loose, tight, coarse, fine)) <= DRIFT_TOL and tight.error < 1e-9


def test_the_reference_agrees_with_mujoco_s_rk4_at_a_fine_step(four_bar, q_end, monkeypatch):
    pytest.importorskip("mujoco")
    monkeypatch.setattr(wp, "MUJOCO", (("RK4",), (1e-3, 1e-4)))
    coarse, fine = wp.mujoco_points(four_bar, q_end, 0.3)
    assert fine.error < 1e-7 and fine.error < coarse.error and fine.closure < coarse.closure


def test_on_the_gripper_mujoco_converges_to_the_reference_at_its_stiff_setting(tmp_path, monkeypatch):
    """The field robot read by both codes, 0.2 s: MuJoCo's RK4 at the stiff setting converges to mechkit's
    reference (1e-8), at the file's softer one it stops at its closure's give (1e-5); one coarse mechkit point
    is within the goal's bounds."""
    pytest.importorskip("mujoco")
    case = wp.field_robot(Path(__file__).resolve().parents[1] / "fixtures" / "field", tmp_path)
    q_end = wp.reference(case.mech, 0.2, case.options)
    monkeypatch.setattr(wp, "MUJOCO", (("RK4",), (1e-3, 2e-4)))
    coarse, fine, soft, soft_fine = wp.mujoco_points(case.mech, q_end, 0.2, case.xml, case.equality)
    assert (coarse.method, soft.method) == ("rk4 stiff", "rk4 file")
    assert fine.error < 1e-8 and fine.error < coarse.error / 10 and min(soft.error, soft_fine.error) > 1e-5
    monkeypatch.setattr(wp, "MECHKIT_ADAPTIVE", (("DOP853", 1e-6),))
    monkeypatch.setattr(wp, "MECHKIT_FIXED", ())
    (point,) = wp.mechkit_points(case.mech, q_end, 0.2, case.options)
    assert point.error < 1e-6 and point.closure <= DRIFT_TOL
    assert "robotiq_2f85" in wp.markdown({case.name: [point]}, {case.name: "x.png"}, {case.name: case.notes})


def test_the_verdict_is_each_code_s_cheapest_run_within_both_bounds():
    points = [
        wp.Point("mechkit", "DOP853", "rtol 1e-07", 5e-7, 1e-16, 0.05, 1000.0),
        wp.Point("mechkit", "DOP853", "rtol 1e-09", 2e-9, 1e-16, 0.09),
        wp.Point("mechkit", "RK45", "rtol 1e-06", 1e-5, 1e-16, 0.01),
        wp.Point("MuJoCo", "rk4", "dt 0.001", 9e-8, 2e-7, 0.01),
    ]
    best = wp.at_equal_accuracy(points)
    assert best["mechkit"] is points[0] and best["MuJoCo"] is None
    assert wp.at_equal_accuracy(points, closure=np.inf)["MuJoCo"] is points[3]
    text = wp.markdown({"four_bar": points}, {"four_bar": "figures/x.png"})
    assert text.startswith(wp.HEADING) and "none meets both" in text and "5.0x MuJoCo's time" in text
    assert "1000 evaluations per simulated s at 50 us each against evaluations not counted" in text
    points.append(wp.Point("MuJoCo", "rk4", "dt 0.0001", 1e-9, 1e-11, 0.04))
    points.append(wp.Point("mechkit", "RK4", "dt 0.001", 1e-5, 1e-16, 0.05))  # same step as MuJoCo's rk4 at 0.01
    assert "within both bounds mechkit takes 1.25x MuJoCo's time: missed" in (
        text := wp.markdown({"x": points}, {"x": "x"})
    )
    assert "same step and order (dt 0.001): mechkit RK4 takes 5x MuJoCo's rk4: missed (goal <= 3x)" in text
