"""The closure model (`mechkit.core.model`): rows chosen once, actuation as a matrix (joint motors and
tendon transmissions), splits of given and solved coordinates, another actuation on the same rows, and
what it refuses (too light bodies, joints not numbered depth first, unknown or multi-freedom motors)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pinocchio as pin
import pytest

from mechkit import core
from mechkit.base.exceptions import InvalidParameters, MalformedDescription


def test_actuation_matrix_of_joint_motors_and_tendons(load_cached):
    m = load_cached("five_bar")
    cm = m.closure_model
    S = cm.actuation
    assert S.shape == (2, m.model.nv) and cm.actuated_v.tolist() == [m.v_index("prox1"), m.v_index("prox2")]
    np.testing.assert_array_equal(S[0, cm.actuated_v], [1.0, 0.0])
    tendon = core.Actuator("tendon", (("prox1", 2.0), ("prox2", -1.0)))
    other = cm.with_actuation(("tendon",), (tendon,))
    assert other.actuated_v is None and other.actuated == ("tendon",)
    np.testing.assert_array_equal(other.actuation[0, cm.actuated_v], [2.0, -1.0])
    assert np.abs(other.actuation @ other.unactuated).max() < 1e-15  # the unactuated motions
    assert other.unactuated.shape == (m.model.nv, m.model.nv - 1)
    assert other.kernel is cm.kernel and other.structure is cm.structure  # the same rows


def test_split_of_given_and_solved_coordinates(load_cached):
    m = load_cached("five_bar")
    split = m.closure_model.split(("prox2",))
    assert split.input_v.tolist() == [m.v_index("prox2")]
    assert sorted(split.input_v.tolist() + split.free_v.tolist()) == list(range(m.model.nv))
    assert m.closure_model.split(("prox2",)) is split  # cached
    with pytest.raises(ValueError):
        split.free_v[0] = 3  # read-only


def test_refusals_name_what_is_wrong(load_cached):
    m = load_cached("four_bar")
    with pytest.raises(InvalidParameters, match="nope"):
        core.ClosureModel(m.model, m.closures, actuated=("nope",))
    with pytest.raises(InvalidParameters, match="named twice"):
        core.ClosureModel(m.model, m.closures, actuated=("crank", "crank"))
    model = pin.Model()
    ball = model.addJoint(0, pin.JointModelSpherical(), pin.SE3.Identity(), "ball")
    model.appendBodyToJoint(ball, pin.Inertia.FromSphere(1.0, 0.1), pin.SE3.Identity())
    with pytest.raises(InvalidParameters, match="3 freedoms"):
        core.ClosureModel(model, (), actuated=("ball",))
    light = m.model.copy()
    light.inertias[1] = pin.Inertia(1e-17, np.zeros(3), np.eye(3) * 1e-20)
    with pytest.raises(InvalidParameters, match="mass of"):
        core.ClosureModel(light, m.closures)


def test_joints_not_numbered_depth_first_are_refused():
    """crba takes a joint's subtree as contiguous velocity columns: a model built breadth first gives a
    wrong mass matrix, so it is refused by name."""
    model = pin.Model()
    a = model.addJoint(0, pin.JointModelRY(), pin.SE3.Identity(), "a")
    model.addJoint(0, pin.JointModelRY(), pin.SE3.Identity(), "b")
    model.addJoint(a, pin.JointModelRY(), pin.SE3.Identity(), "a_child")
    with pytest.raises(MalformedDescription, match="depth first"):
        core.ClosureModel(model, ())


def test_a_model_with_no_moving_joint_is_refused_by_name(tmp_path):
    """Every joint fixed: no coordinate to solve or drive; refused before any array of width 0 is built
    (it was a numpy reshape error), from the library and from the command line (exit 2, one line)."""
    with pytest.raises(MalformedDescription, match="no joint moves"):
        core.ClosureModel(pin.Model(), ())
    still = tmp_path / "still.urdf"
    still.write_text(
        '<robot name="still"><link name="base"/><link name="a"><inertial><mass value="1"/>'
        '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>'
        '<joint name="j" type="fixed"><parent link="base"/><child link="a"/></joint></robot>'
    )
    run = subprocess.run(
        [sys.executable, "-m", "mechkit", "report", str(still)], check=False, capture_output=True, text=True
    )
    assert run.returncode == 2 and run.stderr.strip().splitlines() == [
        "mechkit: error: still: no joint moves (every joint is fixed): there is no mechanism to model"
    ]


def test_scales_are_those_of_the_neutral_configuration(load_cached):
    cm = load_cached("four_bar").closure_model
    data = cm.model.createData()
    q = pin.neutral(cm.model)
    J = core.closure_jacobian(cm, cm.create_data(), q)
    M = pin.crba(cm.model, data, q)
    assert cm.row_scale == pytest.approx(np.max(np.linalg.norm(J, axis=1)), rel=1e-12)
    assert cm.delassus_scale == pytest.approx(cm.row_scale**2 / np.max(np.diag(M)), rel=1e-12)


@pytest.mark.parametrize("name", ["four_bar", "deployable_9rr12uru"])
def test_the_data_views_read_pinocchio_without_a_copy(name, load_cached):
    """`ClosureData.oMi` and `.f` are every joint's placement [R | p] and wrench as Pinocchio holds them
    now, and `used_placements` the homogeneous placements of the joints carrying cut frames."""
    m = load_cached(name)
    cm = m.closure_model
    cd = cm.create_data()
    rng = np.random.default_rng(0)
    q, v, a = pin.randomConfiguration(m.model), rng.normal(size=m.model.nv), rng.normal(size=m.model.nv)
    pin.rnea(m.model, cd.pin, q, v, a)
    placements = cd.pin.oMi.tolist()
    np.testing.assert_array_equal(cd.oMi, np.array([M.homogeneous[:3] for M in placements]))
    np.testing.assert_array_equal(cd.f, np.array([f.vector for f in cd.pin.f.tolist()]))
    np.testing.assert_array_equal(cd.used_placements(), np.array([placements[j].homogeneous for j in cm.kernel.joints]))
    assert not cd.oMi.flags.writeable and not cd.f.flags.writeable
