"""`mechkit.sources.drake_joints`: a chain written with Drake's `drake:joint` types (universal, ball, screw,
planar about a tilted normal) reads as the Pinocchio joints they are; its gravity efforts at a configuration
away from zero equal those of Drake's plant parsing the same file; an unknown type is refused by name."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit.base.exceptions import MalformedDescription


def _link(name: str, mass: float, com: str) -> str:
    return (
        f'<link name="{name}"><inertial><origin xyz="{com}" rpy="0.1 0.2 0.3"/><mass value="{mass}"/>'
        '<inertia ixx="0.02" iyy="0.03" izz="0.04" ixy="0.001" ixz="0" iyz="0.002"/></inertial></link>'
    )


def _joint(tag: str, name: str, kind: str, parent: str, child: str, extra: str = "") -> str:
    return (
        f'<{tag} name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="0.1 0.05 0.3" rpy="0.2 -0.1 0.4"/>{extra}</{tag}>'
    )


CHAIN = (
    '<robot name="chain" xmlns:drake="http://drake.mit.edu"><link name="world"/>'
    + "".join(_link(f"l{k}", 1.0 + 0.3 * k, f"0.1 {0.02 * k} 0.2") for k in range(1, 6))
    + _joint(
        "joint",
        "motor",
        "revolute",
        "world",
        "l1",
        '<axis xyz="0 1 0"/><limit effort="1" lower="-3" upper="3" velocity="1"/>',
    )
    + _joint("drake:joint", "u", "universal", "l1", "l2")
    + _joint("drake:joint", "ball", "ball", "l2", "l3")
    + _joint(
        "drake:joint", "screw", "screw", "l3", "l4", '<axis xyz="0 0.6 0.8"/><drake:screw_thread_pitch value="0.04"/>'
    )
    + _joint("drake:joint", "plane", "planar", "l4", "l5", '<axis xyz="1 0 1"/>')
    + "</robot>"
)


def test_drake_s_joint_types_are_pinocchio_s_and_their_gravity_efforts_are_drake_s(tmp_path):
    """At motor 0.3, universal (0.2, -0.4), ball rpy (0.1, 0.2, 0.3), screw 0.5 rad, planar (0.1, -0.2, 0.3):
    mechkit's gravity torques (Pinocchio's RNEA on the model read) equal Drake's generalised gravity forces,
    the ball's and planar joint's re-expressed from Drake's parent frame F to Pinocchio's child frame M."""
    pytest.importorskip("pydrake")
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    path = tmp_path / "chain.urdf"
    path.write_text(CHAIN)
    m = mechkit.load(path)
    shortnames = [m.model.joints[m.model.getJointId(n)].shortname() for n in ("motor", "u", "ball", "screw", "plane")]
    assert shortnames == [
        "JointModelRY",
        "JointModelUniversal",
        "JointModelSpherical",
        "JointModelHelicalUnaligned",
        "JointModelPlanar",
    ]
    assert (m.model.nq, m.model.nv) == (1 + 2 + 4 + 1 + 4, 1 + 2 + 3 + 1 + 3)
    plant = MultibodyPlant(0.0)
    Parser(plant).AddModels(str(path))
    plant.Finalize()
    assert plant.num_velocities() == m.model.nv
    ctx = plant.CreateDefaultContext()
    rpy, theta = np.array([0.1, 0.2, 0.3]), 0.3
    plant.GetJointByName("motor").set_angle(ctx, 0.3)
    plant.GetJointByName("u").set_angles(ctx, [0.2, -0.4])
    plant.GetJointByName("ball").set_angles(ctx, rpy)
    positions = plant.GetPositions(ctx)
    positions[plant.GetJointByName("screw").position_start()] = 0.5  # its angle (rad)
    plant.SetPositions(ctx, positions)
    plant.GetJointByName("plane").set_pose(ctx, [0.1, -0.2], theta)
    theirs = -plant.CalcGravityGeneralizedForces(ctx)
    q = pin.neutral(m.model)
    values = {
        "motor": [0.3],
        "u": [0.2, -0.4],
        "ball": pin.Quaternion(pin.rpy.rpyToMatrix(*rpy)).coeffs(),
        "screw": [0.5],
        "plane": [0.1, -0.2, np.cos(theta), np.sin(theta)],
    }
    for name, value in values.items():
        jm = m.model.joints[m.model.getJointId(name)]
        q[jm.idx_q : jm.idx_q + jm.nq] = value
    ours = pin.rnea(m.model, m.model.createData(), q, np.zeros(m.model.nv), np.zeros(m.model.nv))
    for name, rotation in (
        ("motor", None),
        ("u", None),
        ("ball", pin.rpy.rpyToMatrix(*rpy)),
        ("screw", None),
        ("plane", pin.exp3(np.array([0.0, 0.0, theta]))),
    ):
        jm, joint = m.model.joints[m.model.getJointId(name)], plant.GetJointByName(name)
        got = ours[jm.idx_v : jm.idx_v + jm.nv]
        want = theirs[joint.velocity_start() : joint.velocity_start() + joint.num_velocities()]
        if name == "ball":
            want = rotation.T @ want
        elif name == "plane":
            want = np.r_[rotation[:2, :2].T @ want[:2], want[2]]
        np.testing.assert_allclose(got, want, rtol=1e-10, atol=1e-10 * np.abs(theirs).max(), err_msg=name)


@pytest.mark.parametrize(
    "replace, match",
    [
        ('type="universal"', "drake:joint 'u'.*type 'curvilinear'"),
        ('<drake:screw_thread_pitch value="0.04"/>', "drake:joint 'screw'.*screw_thread_pitch"),
    ],
)
def test_an_unread_type_or_a_screw_without_pitch_is_refused_by_name(tmp_path, replace, match):
    path = tmp_path / "bad.urdf"
    path.write_text(CHAIN.replace(replace, 'type="curvilinear"' if "type" in replace else ""))
    with pytest.raises(MalformedDescription, match=match):
        mechkit.load(path)
