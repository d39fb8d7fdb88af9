"""Actuators named where input joints are: MJCF tendon actuator, URDF transmission, SDF gearbox input."""

from pathlib import Path

import numpy as np
import pytest

import mechkit
from mechkit.base.exceptions import InvalidArgument

FIELD = Path(__file__).parent / "fixtures" / "field"
GRIPPER = FIELD / "menagerie" / "robotiq_2f85" / "2f85.xml"
FOUR_BAR = Path(mechkit.__file__).parent / "urdf" / "four_bar.urdf"
GEARBOX = FIELD / "sdf" / "four_bar_gearbox.sdf"


@pytest.fixture(scope="module")
def gripper():
    return mechkit.load(GRIPPER)


@pytest.mark.parametrize("opening", [0.1, 0.4, 0.7])
def test_tendon_actuator_fixes_its_length_as_mujoco_measures_it(gripper, opening):
    """assemble by 'fingers_actuator' (a tendon 0.5 right + 0.5 left driver, the drivers tied equal): the
    configuration closes every loop and MuJoCo's own actuator length there is the value given."""
    mujoco = pytest.importorskip("mujoco")
    q = gripper.assemble({"fingers_actuator": opening})
    assert np.linalg.norm(gripper.closure_residual(q)) < 1e-10
    model = mujoco.MjModel.from_xml_path(str(GRIPPER))
    data = mujoco.MjData(model)
    for joint, value in gripper.joint_values(q).items():
        data.qpos[model.joint(joint).qposadr[0]] = value
    mujoco.mj_forward(model, data)
    assert data.actuator_length[model.actuator("fingers_actuator").id] == pytest.approx(opening, abs=1e-12)


def test_tendon_actuator_rates(gripper):
    """velocities by the actuator's name: MuJoCo's actuator moment (dL/dq) times v is the rate given."""
    mujoco = pytest.importorskip("mujoco")
    q = gripper.assemble({"fingers_actuator": 0.4})
    v = gripper.velocities(q, {"fingers_actuator": 0.3}, ["fingers_actuator"], allow_singular=True)
    batch = gripper.velocities_batch(q[None], np.array([[0.3]]), ["fingers_actuator"], allow_singular=True)
    np.testing.assert_allclose(batch[0], v, atol=1e-12)
    model = mujoco.MjModel.from_xml_path(str(GRIPPER))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    # the tendon's joint coefficients are MuJoCo's actuator moment arms (constant for a fixed tendon)
    moment_mj = np.zeros(model.nv)
    mujoco.mju_sparse2dense(
        moment_mj[None], data.actuator_moment, data.moment_rownnz, data.moment_rowadr, data.moment_colind
    )
    v_mj = np.zeros(model.nv)
    for joint in gripper.model.names[1:]:
        v_mj[model.joint(joint).dofadr[0]] = v[gripper.v_index(joint)]
    assert moment_mj @ v_mj == pytest.approx(0.3, abs=1e-12)


def test_urdf_transmission_by_its_name():
    """A URDF <transmission name="crank_transmission"> names the crank: the same assembly and rates, and
    load(actuated=[...]) takes it."""
    m = mechkit.load(FOUR_BAR)
    np.testing.assert_array_equal(m.assemble({"crank_transmission": 0.5}), m.assemble({"crank": 0.5}))
    q = m.assemble({"crank": 0.5})
    np.testing.assert_allclose(m.velocities(q, [1.0], ["crank_transmission"]), m.velocities(q, [1.0], ["crank"]))
    assert m.singularity(q, ["crank_transmission"]) == m.singularity(q, ["crank"])
    assert mechkit.load(FOUR_BAR, actuated=["crank_transmission"]).actuated == ("crank",)


def test_sdf_gearbox_input_by_name():
    """The gearbox fixture's input 'motor' assembles and drives the crank through the gearbox's ratio."""
    m = mechkit.load(GEARBOX)
    assert m.actuated == ("motor",)
    q = m.assemble({"motor": 0.5})
    assert np.linalg.norm(m.closure_residual(q)) < 1e-10
    v = m.velocities(q, {"motor": 1.0})
    assert v[m.v_index("motor")] == 1.0 and v[m.v_index("crank_joint")] != 0.0


def test_unknown_name_lists_joints_and_actuators(gripper):
    """An unknown input name is refused naming the argument and listing the joints and the actuators."""
    with pytest.raises(InvalidArgument, match=r"inputs.*'fingers' is neither.*actuators: \['fingers_actuator'\]"):
        gripper.assemble({"fingers": 0.4})
    with pytest.raises(InvalidArgument, match="inputs.*'fingers' is neither a joint nor an actuator"):
        gripper.velocities(gripper.home_q, [0.1], ["fingers"])


def test_name_and_its_joint_twice_refused(gripper):
    with pytest.raises(InvalidArgument, match="given twice"):
        gripper.assemble({"right_driver_joint": 0.4, "fingers_actuator": 0.4})


def test_tendon_over_untied_joints_refused(tmp_path):
    """A tendon actuator over two joints no equality ties fixes no single joint: refused by name."""
    path = tmp_path / "two.xml"
    path.write_text(
        """<mujoco><worldbody><body name="a"><joint name="j1"/><geom size="0.1" mass="1"/>
        <body name="b" pos="1 0 0"><joint name="j2"/><geom size="0.1" mass="1"/></body></body></worldbody>
        <tendon><fixed name="t"><joint joint="j1" coef="1"/><joint joint="j2" coef="1"/></fixed></tendon>
        <actuator><motor name="m" tendon="t"/></actuator></mujoco>"""
    )
    m = mechkit.load(path)
    with pytest.raises(InvalidArgument, match="'m' drives joints \\['j1', 'j2'\\]"):
        m.assemble({"m": 0.3})
