"""`mechkit.export.mjcf`: the MJCF closes in MuJoCo at another pose and reads back into Pinocchio; it
simulates well (loops stay closed under gravity, geoms, limits, springs, motors)."""

from __future__ import annotations

import re

import numpy as np
import pinocchio as pin
import pytest

from mechkit.catalog import registry
from mechkit.core import AXIS_ANCHOR_OFFSET
from mechkit.export import frame_b_vector, to_mjcf
from mechkit.export.mjcf import SOLREF_DIVISOR, smallest_link_period
from mechkit.mechanisms.ten_bar.params import spring_from_urdf

from .exported import NAMES, other_pose

mujoco = pytest.importorskip("mujoco")


def _mjcf_file(m, tmp_path):
    path = tmp_path / f"{m.spec.name}.xml"
    path.write_text(to_mjcf(m))
    return path


@pytest.mark.parametrize("name", NAMES)
def test_mjcf_closes_in_mujoco_at_another_pose(name, load_cached):
    """MuJoCo's equality residual is zero wherever mechkit's closure is: anchors and coordinates match."""
    m = load_cached(name)
    model = mujoco.MjModel.from_xml_string(to_mjcf(m))
    data = mujoco.MjData(model)
    np.testing.assert_allclose(model.qpos0, m.home_q, atol=1e-15)
    q = other_pose(m)
    data.qpos[:] = q
    mujoco.mj_forward(model, data)
    assert data.nefc > 0
    assert np.max(np.abs(data.efc_pos[: data.nefc])) < 1e-10
    data.qpos[:] = q + 0.01  # off the closure: MuJoCo sees the violation
    mujoco.mj_forward(model, data)
    assert np.max(np.abs(data.efc_pos[: data.nefc])) > 1e-5


@pytest.mark.parametrize("name", NAMES)
def test_mjcf_reads_back_into_pinocchio(name, load_cached, tmp_path):
    """buildModelAndConstraintsFromMJCF gives the same tree (inertias, placements) and closed anchors."""
    m = load_cached(name)
    model, points, frames = pin.buildModelAndConstraintsFromMJCF(str(_mjcf_file(m, tmp_path)))
    assert list(model.names) == list(m.model.names)
    for i in range(1, model.njoints):
        assert model.inertias[i].isApprox(m.model.inertias[i], 1e-12)
    q = other_pose(m)
    d = model.createData()
    pin.forwardKinematics(model, d, q)
    pin.forwardKinematics(m.model, m.data, q)
    for i in range(1, model.njoints):
        assert d.oMi[i].isApprox(m.data.oMi[i], 1e-12)
    assert len(points) + len(frames) >= len(m.closures)
    for c in points:
        gap = (d.oMi[c.joint1_id] * c.joint1_placement).translation - (
            d.oMi[c.joint2_id] * c.joint2_placement
        ).translation
        assert np.linalg.norm(gap) < 1e-10


DRIFT_BOUND = 1e-4  # m, the bound on the loop opening after 1 s under gravity


WORST: dict[str, float] = {}


def _anchor_pairs(m) -> list[tuple[int, int, np.ndarray, np.ndarray]]:
    """(frame_a, frame_b, point in a, same point in b) of every anchor a closed loop makes coincide."""
    pairs = []
    for cut in m.cuts:
        c = cut.closure
        offsets = [np.zeros(3)]
        if c.kind == "revolute" and c.rows != "planar":
            offsets.append(AXIS_ANCHOR_OFFSET * c.axis)
        pairs += [(cut.frame_a, cut.frame_b, p, frame_b_vector(m, cut, p)) for p in offsets]
    return pairs


def _loop_gap(m, data: pin.Data, pairs, q: np.ndarray) -> float:
    """Largest distance (m) between two anchors that coincide on a closed loop, from Pinocchio's kinematics."""
    pin.framesForwardKinematics(m.model, data, q)
    return max(float(np.linalg.norm(data.oMf[a].act(pa) - data.oMf[b].act(pb))) for a, b, pa, pb in pairs)


@pytest.mark.parametrize("name", registry.names())
def test_loops_stay_closed_for_one_second_under_gravity(name, load_cached):
    """Released at home with zero effort, every export keeps its anchors within 1e-4 m for 1 s of MuJoCo."""
    m = load_cached(name)
    model = mujoco.MjModel.from_xml_string(to_mjcf(m))
    data = mujoco.MjData(model)
    pairs = _anchor_pairs(m)
    pdata = m.model.createData()
    assert _loop_gap(m, pdata, pairs, data.qpos.copy()) < 1e-9  # written closed, qpos = mechkit's q
    worst, moved = 0.0, 0.0
    for _ in range(int(np.ceil(1.0 / model.opt.timestep))):
        mujoco.mj_step(model, data)
        worst = max(worst, _loop_gap(m, pdata, pairs, data.qpos.copy()))
        moved = max(moved, float(np.max(np.abs(data.qpos - m.home_q))))
    WORST[name] = worst
    print(
        f"\n{name}: worst loop gap over 1 s {worst:.3g} m (bound {DRIFT_BOUND:g}); joints moved up to {moved:.3g}"
        f" rad or m; timestep {model.opt.timestep:.3g} s; worst so far {max(WORST.values()):.3g} m"
        f" ({max(WORST, key=WORST.get)})"
    )
    assert data.time >= 1.0
    assert moved > 1e-3  # the mechanism really moved under gravity
    assert worst < DRIFT_BOUND


@pytest.mark.parametrize("name", registry.names())
def test_solref_is_the_smallest_link_period_stated_in_a_comment(name, load_cached):
    """Every equality carries solref = (T_min / SOLREF_DIVISOR, 1), and the file says why."""
    m = load_cached(name)
    text = to_mjcf(m)
    model = mujoco.MjModel.from_xml_string(text)
    timeconst = smallest_link_period(m.model) / SOLREF_DIVISOR
    np.testing.assert_allclose(model.eq_solref, np.tile([timeconst, 1.0], (model.neq, 1)), rtol=1e-12)
    assert model.opt.timestep <= timeconst / 2  # MuJoCo's own floor on the time constant
    comment = re.search(r"<!--(.*?)-->", text).group(1)
    assert f"{timeconst:.6g}" in comment and "smallest link period" in comment


def test_link_period_is_the_compound_pendulum_of_a_rod():
    """A uniform rod of length L about one end: T = 2 pi sqrt(2 L / (3 g))."""
    model = pin.Model()
    L, mass = 0.7, 2.0
    j = model.addJoint(0, pin.JointModelRY(), pin.SE3.Identity(), "j")
    model.appendBodyToJoint(
        j,
        pin.Inertia(mass, np.array([L / 2, 0, 0]), np.diag([0, mass * L**2 / 12, mass * L**2 / 12])),
        pin.SE3.Identity(),
    )
    expected = 2 * np.pi * np.sqrt(2 * L / (3 * 9.81))
    assert smallest_link_period(model) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("name", registry.names())
def test_geoms_ranges_and_motors(name, load_cached):
    """Geoms drawn (no contacts), URDF limits as joint ranges, one motor per actuated joint."""
    m = load_cached(name)
    model = mujoco.MjModel.from_xml_string(to_mjcf(m))
    assert model.ngeom > 0
    assert np.all(model.geom_contype == 0) and np.all(model.geom_conaffinity == 0)
    for j in range(1, m.model.njoints):
        jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, m.model.names[j])
        iq = m.model.idx_qs[j]
        assert model.jnt_limited[jid]
        np.testing.assert_array_equal(
            model.jnt_range[jid], [m.model.lowerPositionLimit[iq], m.model.upperPositionLimit[iq]]
        )
    assert model.nu == len(m.actuated)
    for k, joint in enumerate(m.actuated):
        assert model.actuator_trnid[k, 0] == mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint)
    # every mass is the model's: the geoms carry none
    np.testing.assert_allclose(
        model.body_mass[2:], [m.model.inertias[j].mass for j in range(1, m.model.njoints)], rtol=1e-12
    )


def test_ten_bar_spring_gives_the_spring_torque(load_cached):
    """MuJoCo's passive force at R5 is the ten-bar's spring-damper torque k (free - q) - c qdot."""
    m = load_cached("ten_bar")
    spring = spring_from_urdf(m.urdf)
    model = mujoco.MjModel.from_xml_string(to_mjcf(m))
    data = mujoco.MjData(model)
    rng = np.random.default_rng(3)
    data.qpos[:] = m.home_q
    inputs = [*m.actuated, spring.pin]  # the spring's DOF is the third input
    data.qvel[:] = m.velocities(m.home_q, rng.normal(size=len(inputs)), inputs)
    mujoco.mj_forward(model, data)
    v = m.v_index(spring.pin)
    expected = spring.stiffness * (spring.free_angle - m.home_q[v]) - spring.damping * data.qvel[v]
    others = np.delete(data.qfrc_passive, v)
    assert data.qfrc_passive[v] == pytest.approx(expected, rel=1e-12)
    assert abs(expected) > 1.0 and np.all(others == 0)
