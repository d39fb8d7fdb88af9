"""`mechkit.mechanisms.ten_bar.geometry`: mass properties, the closed-form pose, the stowed and
deployed poses clear of the wall."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar import params as tp


def test_mass_properties_match_the_urdf(mech):
    props = geo.mass_properties(mech.params)
    child = {h.child: h.name for h in geo.hinges(mech.params)[:9]}
    for body, (mass, com, inertia) in props.items():
        I = mech.model.inertias[mech.model.getJointId(child[body])]
        assert I.mass == pytest.approx(mass, rel=1e-12)
        assert np.allclose(I.lever[[0, 2]], com, atol=1e-12)
        assert I.inertia[1, 1] == pytest.approx(inertia, rel=1e-12)
    panels = props["l34"][0]
    assert panels == pytest.approx(2.5 * 1.2 * 1.0)  # 1.2 m x 1.0 m at 2.5 kg/m^2


def test_every_loop_closes_for_every_input():
    p = tp.TenBarParams()
    grid = np.linspace(-math.pi, math.pi, 13)
    worst = min(min(geo.pose(p, a, b, c).margins.values()) for a in grid for b in grid for c in grid)
    assert worst > 0.4  # sine of the angle at each closing hinge: far from every dead-centre pose


def test_stowed_and_deployed_poses_and_the_wall():
    p = tp.TenBarParams()
    stowed = geo.stowed_pose(p)
    assert np.allclose(geo.unit(stowed.angles["l123"]), [0, 1]) and np.allclose(geo.unit(stowed.angles["l34"]), [0, -1])
    deployed = geo.pose(p, tp.DEPLOYED["R1"], tp.DEPLOYED["R3"], 0.0)
    R2, R3, R4 = (deployed.points[k] for k in ("R2", "R3", "R4"))
    cross = (R3 - R2)[0] * (R4 - R3)[1] - (R3 - R2)[1] * (R4 - R3)[0]
    assert abs(cross) < 1e-15 and (R3 - R2) @ (R4 - R3) > 0  # collinear, same direction
    assert np.allclose((R4 - R2) / np.linalg.norm(R4 - R2), [1, 0])  # perpendicular to the wall x = 0
    for s in np.linspace(0, 1, 11):  # every hinge and panel end outside the wall over the deployment
        for rocker in np.radians(np.arange(-60, 11, 10)):
            pose = geo.pose(p, math.pi / 2 * (1 - s), -math.pi * (1 - s), rocker)
            assert min(x[0] for k, x in pose.points.items() if k not in ("R1", "R5")) > 0.03
            tip = pose.points["R3"] + p.panel2 * geo.unit(pose.angles["l34"])
            assert tip[0] > 0
