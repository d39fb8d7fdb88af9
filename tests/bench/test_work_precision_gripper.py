"""`mechkit.bench.work_precision_gripper`: the stripped Robotiq 2F-85 is the Menagerie file less its actuator,
and mechkit and MuJoCo hold the same model of it (rigid accelerations on MuJoCo's own matrices equal
mechkit's; MuJoCo's soft ones approach them as its equalities stiffen)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import mechkit
from mechkit.bench import work_precision_gripper as gripper

mujoco = pytest.importorskip("mujoco", reason="MuJoCo not installed: pip install 'mechkit[peers]'")

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures" / "field"


@pytest.fixture(scope="module")
def stripped(tmp_path_factory):
    path = gripper.stripped_file(FIXTURES, tmp_path_factory.mktemp("gripper"))
    return path, mechkit.load(path)


def test_the_copy_drops_the_actuator_and_keeps_the_rest(stripped):
    path, mech = stripped
    original = mujoco.MjModel.from_xml_path(str(FIXTURES / gripper.GRIPPER))
    copy = gripper.mujoco_model(path.read_text())
    assert original.nu == 1 and copy.nu == 0 and copy.neq == original.neq == 3 and copy.ntendon == 1
    for field in ("dof_armature", "dof_damping", "jnt_stiffness", "qpos_spring", "body_mass", "body_inertia"):
        assert np.array_equal(getattr(copy, field), getattr(original, field)), field
    assert np.array_equal(mech.model.armature, copy.dof_armature) and np.all(copy.dof_armature > 0)
    assert copy.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT
    assert copy.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_LIMIT


def test_both_codes_hold_the_same_model(stripped):
    path, mech = stripped
    check = gripper.same_model(mech, path.read_text())
    # rigid on MuJoCo's matrices: round-off; MuJoCo's soft closure: 1e-4 stiff (impedance 0.9999), 7e-2 the file's
    assert check["rigid"] < 1e-10 and check["stiff"] < 1e-3 and check["file"] > 10 * check["stiff"]


def test_the_stiff_rule_is_the_export_s():
    mech = mechkit.load("four_bar")
    solref, solimp = gripper.stiff_equality(mech)
    model = mujoco.MjModel.from_xml_string(mechkit.export.to_mjcf(mech))
    assert np.allclose(model.eq_solref[0], solref, rtol=1e-5) and np.allclose(model.eq_solimp[0], solimp)
