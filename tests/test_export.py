"""Export round trips: MJCF through MuJoCo and Pinocchio's MJCF reader, Extended URDF through its loader."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
import yaml

import mechkit
from mechkit.base.exceptions import MethodUnavailable
from mechkit.cli import main
from mechkit.export import to_extended_urdf, to_mjcf

mujoco = pytest.importorskip("mujoco")

NAMES = ["four_bar", "five_bar", "rocket_gimbal", "spherical_2dof"]


def _other_pose(m) -> np.ndarray:
    """An assembled configuration away from home (the one the MJCF is written at)."""
    home = np.array([m.home_q[m.q_index(j)] for j in m.actuated])
    return m.assemble(home + 0.02, guess=m.home_q)


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
    q = _other_pose(m)
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
    q = _other_pose(m)
    d = model.createData()
    pin.forwardKinematics(model, d, q)
    pin.forwardKinematics(m.model, m.data, q)
    for i in range(1, model.njoints):
        assert d.oMi[i].isApprox(m.data.oMi[i], 1e-12)
    assert len(points) + len(frames) >= len(m.closures)
    for c in points:
        gap = (d.oMi[c.joint1_id] * c.joint1_placement).translation - (d.oMi[c.joint2_id] * c.joint2_placement).translation
        assert np.linalg.norm(gap) < 1e-10


@pytest.mark.parametrize("name", NAMES)
def test_extended_urdf_round_trip_gives_the_same_dynamics(name, load_cached):
    """The tree URDF + YAML sidecar, read as Gepetto's loader does, reproduce mechkit's constrained dynamics."""
    m = load_cached(name)
    urdf, sidecar = to_extended_urdf(m)
    model, constraints, motors = load_extended_urdf(urdf, sidecar)
    assert motors == list(m.actuated)
    q = _other_pose(m)
    v = m.velocities(q, np.ones(len(m.actuated)))
    tau = np.zeros(m.model.nv)
    tau[m.v_index(m.actuated[0])] = 0.3
    cms = pin.StdVec_RigidConstraintModel()
    for c in constraints:
        cms.append(c)
    cds = pin.StdVec_RigidConstraintData()
    for c in cms:
        cds.append(c.createData())
    data = model.createData()
    pin.initConstraintDynamics(model, data, cms, cds)
    a = pin.constraintDynamics(model, data, q, v, tau, cms, cds, pin.ProximalSettings(1e-12, 1e-9, 30))
    expected = m.forward_dynamics(q, v, tau, "kkt").a
    assert np.max(np.abs(a - expected)) <= 1e-8 * max(1.0, np.max(np.abs(expected)))


def test_hooke_cut_has_no_export():
    """A Hooke cut has no MJCF equality nor sidecar pair: a clear MethodUnavailable, not a wrong file."""
    urdf = """<robot name="h" xmlns:mechkit="https://mechkit.dev/loop">
      <link name="base"/>
      <link name="arm"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit effort="1" lower="-3" upper="3" velocity="1"/></joint>
      <link name="arm2"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="j2" type="revolute"><parent link="arm"/><child link="arm2"/><origin xyz="0.5 0 0"/><axis xyz="0 0 1"/>
        <limit effort="1" lower="-3" upper="3" velocity="1"/></joint>
      <link name="arm_tip"/><joint name="arm_tip_fixed" type="fixed"><parent link="arm2"/><child link="arm_tip"/>
        <origin xyz="0.5 0 0"/></joint>
      <link name="base_tip"/><joint name="base_tip_fixed" type="fixed"><parent link="base"/><child link="base_tip"/>
        <origin xyz="1 0 0"/></joint>
      <mechkit:loop name="U" type="hooke" frame_a="base_tip" frame_b="arm_tip" axis_a="1 0 0" axis_b="0 1 0"/>
    </robot>"""
    m = mechkit.from_urdf(urdf, actuated=["j1"])
    with pytest.raises(MethodUnavailable, match="hooke"):
        to_mjcf(m)
    with pytest.raises(MethodUnavailable, match="hooke"):
        to_extended_urdf(m)


def test_cli_export_writes_both_formats(tmp_path, capsys):
    assert main(["export", "four_bar", "--format", "mjcf", "-o", str(tmp_path / "fb.xml")]) == 0
    assert main(["export", "four_bar", "--format", "extended-urdf", "-o", str(tmp_path / "fb.urdf")]) == 0
    out = capsys.readouterr().out
    assert "fb.xml" in out and "fb.yaml" in out
    mujoco.MjModel.from_xml_path(str(tmp_path / "fb.xml"))
    sidecar = yaml.safe_load((tmp_path / "fb.yaml").read_text())
    assert sidecar == {"closed_loop": [["coupler_C", "rocker_C"]], "type": ["3d"], "name_mot": ["crank"],
                       "joint_name": [], "joint_type": []}


def load_extended_urdf(urdf: str, yaml_text: str) -> tuple[pin.Model, list[pin.RigidConstraintModel], list[str]]:
    """An independent reader for the round trip: an Extended URDF pair read the way Gepetto's loader does (model, RigidConstraintModels, motors),
    for pairs without substitutions (mechkit's exports).

    Every pair is a point (3d) or frame (6d) anchor, as in Gepetto's toolbox; `read_extended_urdf`
    is mechkit's reading (joints, not anchors).

    Args:
        urdf: tree URDF text.
        yaml_text: sidecar text (`closed_loop`, `type`, `name_mot`).
    """
    import yaml

    content = yaml.safe_load(yaml_text)
    model = pin.buildModelFromXML(urdf)
    constraints = []
    for (name_a, name_b), kind in zip(content["closed_loop"], content["type"], strict=True):
        fa, fb = (model.frames[model.getFrameId(n)] for n in (name_a, name_b))
        contact = pin.ContactType.CONTACT_3D if kind.lower() == "3d" else pin.ContactType.CONTACT_6D
        constraints.append(pin.RigidConstraintModel(contact, model, fa.parentJoint, fa.placement, fb.parentJoint,
                                                    fb.placement, pin.ReferenceFrame.LOCAL))
    return model, constraints, list(content["name_mot"])
