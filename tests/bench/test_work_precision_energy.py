"""`mechkit.bench.work_precision_energy`: one energy balance for both codes. mechkit's converged run keeps it to
round-off; MuJoCo's RK4 drift falls with its step at the stiff setting; on the damped gripper the balance closes
only with the dampers' work counted."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechkit.bench import work_precision as wp
from mechkit.bench import work_precision_energy as energy
from mechkit.bench import work_precision_gripper as gripper

mujoco = pytest.importorskip("mujoco", reason="MuJoCo not installed: pip install 'mechkit[peers]'")


def _mujoco(case, integrator: str, dt: float):
    model = gripper.mujoco_model(case.xml, case.equality["stiff"])
    model.opt.timestep, model.opt.integrator = dt, getattr(mujoco.mjtIntegrator, f"mjINT_{integrator}")
    return model


def test_the_balance_is_relative_to_its_largest_term():
    t = np.linspace(0.0, 1.0, 11)
    kinetic, potential = 2.0 * t, -2.0 * t + 1e-3 * t**2  # a drift of 1e-3 J against terms changing by 2 J
    assert energy.balance_error(kinetic, potential, np.zeros_like(t)) == pytest.approx(5e-4, rel=1e-12)


def test_the_four_bar_s_balance_in_both_codes():
    case = wp.exported("four_bar")
    run = case.mech.simulate(0.3, method="DOP853", rtol=1e-12, atol=1e-14, reactions=False, limits=None)
    assert energy.mechkit_energy_error(run) < 1e-10
    coarse, fine = (
        energy.mujoco_energy_error(_mujoco(case, "RK4", dt), case.mech.home_q, round(0.3 / dt)) for dt in (2e-3, 2e-4)
    )
    assert fine < coarse / 100 and fine < 1e-7  # RK4: 10^4 expected; measured 4.9e-6 and 1.1e-8


def test_the_damped_gripper_s_balance_counts_the_dampers(tmp_path):
    case = wp.field_robot(Path(__file__).resolve().parents[1] / "fixtures" / "field", tmp_path)
    run = case.mech.simulate(0.2, method="DOP853", rtol=1e-12, atol=1e-14, reactions=False, limits=None, **case.options)
    assert energy.mechkit_energy_error(run) < 1e-10 and run.dissipated[-1] > 0.1 * np.ptp(run.kinetic)
    undamped = energy.balance_error(run.kinetic, run.gravity + run.potentials.sum(axis=1), 0 * run.kinetic)
    assert undamped > 0.01  # the dampers' work is part of the balance
    assert energy.mujoco_energy_error(_mujoco(case, "RK4", 2e-4), case.mech.home_q, 1000) < 1e-6  # measured 5.5e-8
