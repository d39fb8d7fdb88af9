"""`mechkit.mechanisms.parallel_2t1r.studies`: the start of the motion law and the approach to the
singular pose."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.parallel_2t1r.studies import singular_approach, start_of_motion


def test_start_of_motion_law(mech):
    """t -> 0+: torques tend to finite limits, cond(J_p) and the five-bar's R13 force grow as 1/t;
    at t = 0 every method raises SingularConfiguration (none returns NaN)."""
    times = np.array([1e-1, 1e-2, 1e-3, 1e-4, 0.0])
    study = start_of_motion(mech, times)
    v = study.values
    for key in ("cond_Jp", "pinocchio:R13_fx"):
        slope = np.polyfit(np.log(times[:4]), np.log(np.abs(v[key][:4])), 1)[0]
        assert slope == pytest.approx(-1.0, abs=0.01)
    for method in ("classic", "soc", "pinocchio"):
        m1 = v[f"{method}:M1"][:4]
        assert np.ptp(m1) < 1e-3 * np.abs(m1).max()
    assert {m for m, fails in study.failures.items() if [x for x, _ in fails] == [0.0]} == {
        "analytic",
        "classic",
        "soc",
        "pinocchio",
    }


def test_singular_approach_blows_up_only_without_redundant_actuation(mech):
    deltas = np.array([1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 0.0])
    study = singular_approach(mech, deltas)
    v, x = study.values, deltas[:-1]
    for key in ("cond_Jp", "classic:cond", "soc:M1", "pinocchio:M1", "pinocchio:M2", "pinocchio:R13_fx"):
        slope = np.polyfit(np.log(x[2:]), np.log(np.abs(v[key][2:-1])), 1)[0]
        assert slope == pytest.approx(-0.5, abs=0.02), key
        assert np.abs(v[key][3:-1]).max() / np.abs(v[key][:3]).max() > 20.0, key
    for key in (
        "redundant/classic:M1",
        "redundant/classic:M2",
        "redundant/classic:M3",
        "redundant/classic:M4",
        "redundant/classic:cond",
        "redundant/pinocchio:R13_fx",
        "redundant/soc:R23_fx",
    ):
        growth = np.abs(v[key][3:-1]).max() / np.abs(v[key][:3]).max()  # 31.6 for delta^-1/2
        assert growth < 1.5, key
    for q in ("M1", "M2", "M3", "M4"):  # converging like delta^1/2 to the value at the singular pose
        gap = np.abs(v[f"redundant/classic:{q}"][3:-1] - v[f"redundant/classic:{q}"][-1])
        assert gap[2] < 0.2 * gap[0], q
    for method in ("classic", "soc", "pinocchio"):  # the plain variant: a clear error at delta = 0
        assert [x for x, _ in study.failures[method]] == [0.0]
    for q in ("M1", "M2", "M3"):  # SOC and Pinocchio, handed M4, reproduce the minimum-norm torques
        ref = v[f"redundant/classic:{q}"][:-1]
        for method in ("soc", "pinocchio"):
            np.testing.assert_allclose(v[f"redundant/{method}:{q}"][:-1], ref, rtol=0, atol=1e-7 * np.abs(ref).max())
    for q in ("R23_fx", "R23_fz", "R43_fx", "R43_fz"):
        ref = v[f"redundant/pinocchio:{q}"][:-1]
        np.testing.assert_allclose(v[f"redundant/soc:{q}"][:-1], ref, rtol=0, atol=1e-7 * np.abs(ref).max())
