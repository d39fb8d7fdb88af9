"""`mechkit.simulation.initial`: one crank's rate gives the N four-bar's whole parallelogram, rates the loops
do not allow together are refused by name, and an MJCF keyframe's qvel (hinge, ball, free joint) carries
the kinetic energy MuJoCo computes for it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit.base.exceptions import InvalidArgument
from mechkit.simulation.initial import keyframe_velocity, rates_velocity

FOUR_BARS = Path(__file__).resolve().parents[1] / "fixtures" / "iftomm" / "n_four_bar.urdf"


def test_one_crank_rate_moves_the_whole_parallelogram():
    """crank0 at -1 rad/s at home (cranks upright): every crank at -1 rad/s, every coupler at +1 (they
    translate), and J v = 0."""
    m = mechkit.load(FOUR_BARS)
    v = rates_velocity(m, {"crank0": -1.0}, m.home_q)
    for j in ("crank0", "crank1", "crank2"):
        assert v[m.v_index(j)] == pytest.approx(-1.0, abs=1e-12)
    for j in ("coupler1", "coupler2"):
        assert v[m.v_index(j)] == pytest.approx(1.0, abs=1e-12)
    assert np.max(np.abs(m.closure_jacobian(m.home_q) @ v)) < 1e-12


@pytest.mark.parametrize(
    "rates, needle",
    [
        ({"crank0": -1.0, "crank1": 2.0}, "do not allow these rates together"),
        ({"crankX": 1.0}, "no such joint"),
        ({"crank0": float("nan")}, "finite"),
    ],
)
def test_rates_the_loops_refuse_are_named(rates, needle):
    m = mechkit.load(FOUR_BARS)
    with pytest.raises(InvalidArgument, match=needle):
        rates_velocity(m, rates, m.home_q, "--v0")


MJCF = """<mujoco model="keyframed">
  <worldbody>
    <body name="arm" pos="0 0 1"><joint name="hinge" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.05" mass="1"/>
      <body name="tip" pos="0.5 0 0"><joint name="ball" type="ball"/>
        <geom type="box" size="0.1 0.05 0.02" pos="0.1 0 0" mass="0.5"/></body></body>
    <body name="block" pos="1 1 1" euler="20 30 40"><freejoint name="free"/>
      <geom type="box" size="0.2 0.1 0.05" mass="2"/></body>
  </worldbody>
  <keyframe><key name="home" qpos="0.3  0.9 0.1 0.3 0.3  1 1 1 0.8 0.2 0.4 0.4"
                 qvel="1.5  0.3 -0.7 0.2  0.4 -0.3 0.9 1.1 -0.6 0.25"/></keyframe>
</mujoco>
"""


def test_a_keyframe_qvel_carries_mujocos_kinetic_energy(tmp_path):
    """A hinge, a ball below it and a free block, keyframe "home" with qpos and qvel: Pinocchio's kinetic
    energy of the velocity read equals MuJoCo's (mj_energyVel) for the same state, to 1e-12 J (the free
    joint's linear velocity is turned from MuJoCo's world frame into Pinocchio's body frame)."""
    mujoco = pytest.importorskip("mujoco")
    path = tmp_path / "keyframed.xml"
    path.write_text(MJCF)
    m = mechkit.load(path)
    v = keyframe_velocity(m, path, m.home_q)
    mm = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(mm)
    mujoco.mj_resetDataKeyframe(mm, d, 0)
    mm.opt.enableflags |= mujoco.mjtEnableBit.mjENBL_ENERGY
    mujoco.mj_forward(mm, d)
    kinetic = pin.computeKineticEnergy(m.model, m.model.createData(), m.home_q, v)
    assert kinetic == pytest.approx(float(d.energy[1]), abs=1e-12) and kinetic > 1.0
    assert keyframe_velocity(m, path, m.home_q, key="nope") is None
