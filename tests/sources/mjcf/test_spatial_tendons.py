"""`mechkit.sources.mjcf.spatial_tendons`: a double pendulum held by a spatial tendon spring and damper and
pulled by a motor on a second tendon (tests/fixtures/tendon_pendulum.xml, ours), simulated by mechkit and by
MuJoCo from the same file; what is read, and what is refused by name."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import scipy.interpolate

import mechkit
from mechkit.base.exceptions import MalformedDescription

mujoco = pytest.importorskip("mujoco")

FIXTURE = Path(__file__).resolve().parents[2] / "fixtures" / "tendon_pendulum.xml"


def _mujoco_positions(path: Path, times, timestep: float) -> np.ndarray:
    """MuJoCo's qpos at `times` from the keyframe "home", RK4 at `timestep`."""
    mm = mujoco.MjModel.from_xml_path(str(path))
    mm.opt.timestep = timestep
    data = mujoco.MjData(mm)
    mujoco.mj_resetDataKeyframe(mm, data, 0)
    out = []
    for t in times:
        while data.time < t - 0.5 * timestep:
            mujoco.mj_step(mm, data)
        out.append(data.qpos.copy())
    return np.array(out)


def test_the_tendons_are_read_as_point_to_point_elements():
    """The spring-damper tendon and the motor's tendon (force gear x ctrl of the keyframe: 2 x 1.5 N)."""
    m = mechkit.load(str(FIXTURE))
    read = mechkit.forces.read_described(FIXTURE, None, m.model).struts
    by_name = {s.name: s for s in read}
    iso, winch = by_name["isolator"], by_name["winch"]
    assert (iso.frame_a, iso.frame_b, iso.stiffness, iso.damping, iso.free_length) == ("anchor", "tip", 40.0, 0.4, 0.3)
    assert (winch.frame_a, winch.frame_b, winch.stiffness, winch.damping) == ("pull", "mid", 0.0, 0.0)
    assert winch.force == pytest.approx(3.0)


@pytest.mark.parametrize(
    "actuator",
    [
        '<motor name="winch" tendon="cable" gear="2"/>',
        '<position name="winch" tendon="cable" gear="2" kp="30" kv="0.5"/>',  # a spring and damper to ctrl / gear
    ],
)
def test_trajectory_agrees_with_mujoco(tmp_path, actuator):
    """1 s from the keyframe, the winch a motor or a position servo: mechkit (RK45 at rtol 1e-10) and MuJoCo
    (RK4, dt 1e-4 s) agree to 2e-8 rad at 0.25, 0.5 and 1 s (measured 3e-9; MuJoCo's own step error, against
    dt 5e-5 s, is below 1e-9), with the pendulum swinging through more than 0.2 rad, and mechkit's energy
    balance closes to 1e-9 of the energy exchanged."""
    path = _variant(tmp_path, '<motor name="winch" tendon="cable" gear="2"/>', actuator)
    m = mechkit.load(str(path))
    times = [0.25, 0.5, 1.0]
    reference = _mujoco_positions(path, times, 1e-4)
    assert np.max(np.abs(reference - _mujoco_positions(path, times, 5e-5))) < 1e-9
    assert np.allclose(m.home_q, [0.3, -0.4])  # the keyframe MuJoCo starts from
    run = m.simulate(1.0, source=path, rtol=1e-10, atol=1e-12)
    ours = scipy.interpolate.CubicSpline(run.t, run.motion.q)(times)
    assert np.ptp(run.motion.q[:, 0]) > 0.2
    assert np.max(np.abs(ours - reference)) < 2e-8
    assert run.energy_error <= 1e-9 * run.energy_scale


def _variant(tmp_path: Path, old: str, new: str) -> Path:
    path = tmp_path / "variant.xml"
    text = FIXTURE.read_text()
    assert re.search(re.escape(old), text)
    path.write_text(text.replace(old, new))
    return path


@pytest.mark.parametrize(
    "old, new, match",
    [
        ('<site site="tip"/>', '<site site="mid"/><site site="tip"/>', "two sites only"),
        ('springlength="0.3"', 'springlength="0.3 0.35"', "dead band"),
        ('gear="2"/>', 'gear="2" forcerange="-1 1"/>', "force range"),
        ('name="isolator" ', 'name="isolator" limited="true" range="0 1" ', "length limits"),
    ],
)
def test_what_is_not_read_is_refused_by_name(tmp_path, old, new, match):
    with pytest.raises(MalformedDescription, match=match):
        mechkit.load(str(_variant(tmp_path, old, new)))
