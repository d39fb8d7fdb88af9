"""`mechkit.sources.rebuilt_tree.rebuild`: a replaced, split or locked joint leaves every body and frame where
the original tree puts them at the matching configuration, and the mass unchanged."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.sources.rebuilt_tree import rebuild


def _tree() -> pin.Model:
    model = pin.Model()
    parent, frame = 0, 0
    for k, joint in enumerate((pin.JointModelRX(), pin.JointModelRY(), pin.JointModelRZ()), 1):
        parent = model.addJoint(
            parent, joint, pin.SE3(pin.exp3(np.array([0.1, 0.2, 0.3 * k])), np.ones(3) * k), f"j{k}"
        )
        frame = model.addJointFrame(parent, frame)
        model.appendBodyToJoint(parent, pin.Inertia.Random(), pin.SE3.Identity())
        model.addFrame(pin.Frame(f"f{k}", parent, frame, pin.SE3.Random(), pin.FrameType.OP_FRAME), False)
    return model


def _frames(model: pin.Model, q: np.ndarray) -> dict[str, np.ndarray]:
    data = model.createData()
    pin.framesForwardKinematics(model, data, q)
    return {f.name: data.oMf[i].homogeneous for i, f in enumerate(model.frames) if f.name.startswith("f")}


def test_a_replaced_split_and_locked_joint_keep_the_frames_and_the_mass():
    model = _tree()
    new = rebuild(model, {2: pin.JointModelSpherical()}, {1: ("X", "Y")}, [3])
    assert [new.joints[j].shortname() for j in range(1, new.njoints)] == [
        "JointModelRX",
        "JointModelRY",
        "JointModelSpherical",
    ]
    rotation = pin.exp3(np.array([0.0, 0.4, 0.0]))
    q = np.r_[0.7, 0.0, pin.Quaternion(rotation).coeffs()]  # j1 = 0.7 about X, j2 = 0.4 about Y, j3 locked at 0
    want, got = _frames(model, np.array([0.7, 0.4, 0.0])), _frames(new, q)
    for name in want:
        np.testing.assert_allclose(got[name], want[name], atol=1e-12, err_msg=name)
    assert abs(sum(i.mass for i in new.inertias) - sum(i.mass for i in model.inertias)) < 1e-14
