"""`mechkit.sweep.metrics`: the motion study's physics (power balance, the weight on the ground pins)."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit.sweep import Study
from mechkit.sweep.metrics import motion_samples

from .chunks import four_bar_rows


def test_motion_study_power_balance():
    """tau * omega = d(kinetic + potential energy)/dt along a crank turn at constant speed."""
    mech = mechkit.load("four_bar")
    study = Study(law="turn", samples=400)
    s = motion_samples(mech, study)
    omega = 2 * math.pi / study.period
    energy = []
    for q in s.q:
        v = mech.velocities(q, [omega])
        energy.append(
            pin.computeKineticEnergy(mech.model, mech.data, q, v) + pin.computePotentialEnergy(mech.model, mech.data, q)
        )
    dE = (np.roll(energy, -1) - np.roll(energy, 1)) / (2 * study.period / study.samples)  # periodic motion
    power = s.efforts[:, 0] * omega
    assert np.max(np.abs(power - dE)) < 2e-3 * np.max(np.abs(power))
    assert np.max(s.residual) < 1e-9
    assert np.all(s.inv_cond > 0)


def test_ground_pins_carry_the_weight():
    """Quasi-statically slow, the two ground pins (crank at A, rocker at D) carry the linkage's weight:
    |f_A| + |f_D| >= m g at every sample, with equality of the vertical sum (checked through the
    peak columns' lower bound)."""
    mech = mechkit.load("four_bar")
    s = motion_samples(mech, Study(law="turn", samples=40, period=1e4))
    weight = 9.81 * sum(i.mass for i in mech.model.inertias)
    pins = s.forces[:, [s.joints.index("crank"), s.joints.index("rocker")]].sum(axis=1)
    assert np.all(pins >= weight * (1 - 1e-9))
    rows, _ = four_bar_rows([[0.10, 0.30]], Study(law="turn", samples=40, period=1e4), ("peak_force", "peak_effort"))
    assert rows[0]["peak_force.crank"] + rows[0]["peak_force.rocker"] >= weight * (1 - 1e-9)
    assert rows[0]["peak_force.crank"] == pytest.approx(s.forces[:, s.joints.index("crank")].max(), rel=1e-9)
