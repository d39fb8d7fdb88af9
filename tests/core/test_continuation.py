"""The assembly branch: continuation from a reference, revolute angles wrapped into their limits.

The Robotiq 2F-85 (MuJoCo Menagerie) closes each finger by an MJCF `connect` equality and ties the
drivers by a joint equality; MuJoCo 4.0.0 computes its own residual of those equalities (`efc_pos` of
the equality rows after `mj_forward`), an independent check of the poses mechkit assembles.
"""

from pathlib import Path

import numpy as np
import pytest

import mechkit
from mechkit.core import continuation
from mechkit.core.continuation import wrap_into_limits

GRIPPER = Path(__file__).parents[1] / "fixtures" / "field" / "menagerie" / "robotiq_2f85" / "2f85.xml"
FOUR_BAR = Path(mechkit.__file__).parent / "urdf" / "four_bar.urdf"


@pytest.fixture(scope="module")
def gripper():
    return mechkit.load(GRIPPER)


def _mujoco_equality_residual(m, q) -> tuple[float, float]:
    """MuJoCo's own equality residual (m and rad) and actuator length at mechkit's configuration q."""
    mujoco = pytest.importorskip("mujoco")
    model = mujoco.MjModel.from_xml_path(str(GRIPPER))
    data = mujoco.MjData(model)
    for joint, value in m.joint_values(q).items():
        data.qpos[model.joint(joint).qposadr[0]] = value
    mujoco.mj_forward(model, data)
    rows = data.efc_type == mujoco.mjtConstraint.mjCNSTR_EQUALITY
    assert rows.sum() == 7  # two connects (3 rows each) and the drivers' joint equality
    return float(np.max(np.abs(data.efc_pos[rows]))), float(data.actuator_length[0])


@pytest.mark.parametrize("opening", [0.1, 0.45, 0.8])
def test_gripper_by_its_actuator_in_range_on_the_home_branch(gripper, opening):
    """At three openings (0.8 the driver's upper limit): every joint in its range, the home's branch
    (continued from it), and MuJoCo's own equality residual at round-off (its equalities are soft at
    solve time, but their residual is geometry: 1e-12 is round-off of 0.1 m links)."""
    a = gripper.assembly({"fingers_actuator": opening})
    q = a.q
    assert a.branch == "continued from the home assembly"
    assert a.outside == ()
    assert np.array_equal(gripper.assemble({"fingers_actuator": opening}), q)
    lo, hi = gripper.model.lowerPositionLimit, gripper.model.upperPositionLimit
    assert np.all(q >= lo - 1e-9) and np.all(q <= hi + 1e-9)
    residual, length = _mujoco_equality_residual(gripper, q)
    assert residual < 1e-12
    assert length == pytest.approx(opening, abs=1e-12)
    # the home's branch: both fingers alike (the file is mirror-symmetric), coupler bent the home's way
    values = gripper.joint_values(q)
    for side in ("coupler", "spring_link", "follower"):
        assert values[f"right_{side}_joint"] == pytest.approx(values[f"left_{side}_joint"], abs=1e-2)
    assert values["right_coupler_joint"] < 0


def test_gripper_motion_keeps_its_branch(gripper):
    """Along openings 0 -> 0.8 by 0.02, each sample continued from the previous one: no joint moves more
    than the input between samples (a branch jump moves the coupler by about a radian)."""
    q, step = gripper.home_q, 0.02
    for opening in np.arange(step, 0.8 + 1e-9, step):
        a = gripper.assembly({"fingers_actuator": opening}, reference=q)
        new = a.q
        assert a.branch == "continued from the reference given"
        assert np.max(np.abs(new - q)) <= step * (1 + 1e-6)
        q = new
    assert _mujoco_equality_residual(gripper, q)[0] < 1e-12


def test_four_bar_keeps_the_reference_branch_not_the_guess():
    """The four-bar's crossed and open assemblies: continued from a closed reference (or a closed guess) on
    either branch, the result stays on that branch (the rocker angle's side), and both close the loop."""
    m = mechkit.load(FOUR_BAR)
    home = m.home_q
    rocker = m.q_index("rocker")
    other = m.assemble({"crank": float(home[m.q_index("crank")])}, guess={"rocker": -home[rocker]})
    assert np.linalg.norm(m.closure_residual(other)) < 1e-10
    if abs(other[rocker] - home[rocker]) < 1e-3:
        pytest.skip("the guess did not reach the other branch")
    for reference, how in [(r, how) for r in (home, other) for how in ("reference", "guess")]:
        a = m.assembly({"crank": float(home[m.q_index("crank")]) + 0.3}, **{how: reference})  # a closed guess too
        q = a.q
        assert a.branch == f"continued from the {'reference given' if how == 'reference' else 'closed guess given'}"
        assert np.linalg.norm(m.closure_residual(q)) < 1e-10
        assert abs(q[rocker] - reference[rocker]) < abs(q[rocker] - (home if reference is other else other)[rocker])


def test_wrap_into_limits_shifts_whole_turns_and_names_the_rest(gripper):
    """An angle off by whole turns comes back into its range with the same placement; one no shift
    brings in is named."""
    q = gripper.assemble({"fingers_actuator": 0.45})
    i = gripper.q_index("right_coupler_joint")
    turned = q.copy()
    turned[i] += 4 * np.pi
    back, outside = wrap_into_limits(gripper.model, turned)
    assert back[i] == pytest.approx(q[i], abs=1e-12) and outside == ()
    turned[gripper.q_index("right_driver_joint")] = 1.5  # range [0, 0.8]: no whole turn brings it in
    assert wrap_into_limits(gripper.model, turned)[1] == ("right_driver_joint",)
    unset = gripper.model.copy()  # lower = upper (a URDF's "0 0", as Gepetto's files write): no bound
    i = gripper.q_index("right_driver_joint")
    unset.lowerPositionLimit[i] = unset.upperPositionLimit[i] = 0.0
    assert wrap_into_limits(unset, turned)[1] == ()


@pytest.mark.parametrize("opening", [0.1, 0.45, 0.75])
def test_gripper_agrees_with_mujocos_settled_pose(gripper, opening):
    """MuJoCo 4.0.0 settles the gripper (gravity off, its position actuator at the opening, 5000 steps
    to |qvel| ~ 1e-11): each finger has a second freedom (the pad), which MuJoCo's spring holds against
    the coupler's stop at 0. Given MuJoCo's actuator length and those coupler values, mechkit's assembly
    gives the other six joints within MuJoCo's softness: its equalities settle with gaps |efc_pos| of
    ~5e-6 m, an angle error of gap / link length, bounded by 50 * gap (links over 0.02 m; ours); measured
    1.6e-4 rad at 0.1, 7e-5 at 0.45 and 0.75. The couplers sit 1e-4 rad past their stop (MuJoCo's soft
    limit), which the assembly's `outside` names."""
    mujoco = pytest.importorskip("mujoco")
    model = mujoco.MjModel.from_xml_path(str(GRIPPER))
    model.opt.gravity[:] = 0
    data = mujoco.MjData(model)
    data.ctrl[0] = opening * 255 / 0.8  # the file's ctrlrange [0, 255] spans the drivers' [0, 0.8]
    for _ in range(5000):
        mujoco.mj_step(model, data)
    assert np.max(np.abs(data.qvel)) < 1e-8
    names = list(gripper.model.names[1:])
    settled = np.array([data.qpos[model.joint(n).qposadr[0]] for n in names])
    gap = float(np.max(np.abs(data.efc_pos[data.efc_type == mujoco.mjtConstraint.mjCNSTR_EQUALITY])))
    couplers = {j: settled[names.index(j)] for j in ("right_coupler_joint", "left_coupler_joint")}
    a = gripper.assembly({"fingers_actuator": float(data.actuator_length[0]), **couplers})
    assert a.branch == "continued from the home assembly"
    assert np.max(np.abs(a.q - settled)) < 50 * gap
    assert set(a.outside) == {j for j, v in couplers.items() if v > 1e-9}


XARM = Path(__file__).parents[1] / "fixtures" / "field" / "menagerie" / "ufactory_xarm7" / "hand.xml"


def _mujoco_settled(path: Path, names: list[str], ctrl: float, steps: int):
    """MuJoCo 4.0.0's settled pose (gravity off, the actuator's control at ctrl, `steps` steps): the joints'
    values in `names` order, the actuator length, the largest |qvel|."""
    mujoco = pytest.importorskip("mujoco")
    model = mujoco.MjModel.from_xml_path(str(path))
    model.opt.gravity[:] = 0
    data = mujoco.MjData(model)
    data.ctrl[0] = ctrl
    for _ in range(steps):
        mujoco.mj_step(model, data)
    settled = np.array([data.qpos[model.joint(n).qposadr[0]] for n in names])
    return settled, float(data.actuator_length[0]), float(np.max(np.abs(data.qvel)))


@pytest.mark.parametrize("opening", [0.1, 0.4, 0.8])
def test_xarm_gripper_by_its_actuator_in_range_on_the_files_branch(opening):
    """The xArm gripper (Menagerie, BSD-3): each finger a four-bar closed by a `connect`, DOF 1. By its
    actuator at three openings (its joints' range [0, 0.85]): continued from the file's qpos0, every joint
    in range, on the file's branch (the parallelogram: each joint turns with its driver, where the other
    assembly folds the finger), MuJoCo's own equality residual at round-off and its tendon length the
    opening. Against MuJoCo's settled pose (20000 steps to |qvel| < 1e-6; its control sets the length
    0.333 ctrl / 100): mechkit's closed pose with MuJoCo's length is within |e| / sigma_min of it, e the
    closure residual of MuJoCo's soft pose and sigma_min the passive block's smallest singular value
    (the first-order distance to the nearest closed pose; measured 0.27, 0.33, 0.52 of that bound)."""
    mujoco = pytest.importorskip("mujoco")
    hand = mechkit.load(XARM)
    assert hand.home_mobility.dof == 1 and len(hand.closures) == 2
    a = hand.assembly({"fingers_actuator": opening})
    assert a.branch == "continued from the home assembly" and a.outside == ()
    lo, hi = hand.model.lowerPositionLimit, hand.model.upperPositionLimit
    assert np.all(a.q >= lo - 1e-9) and np.all(a.q <= hi + 1e-9)
    assert np.max(np.abs(a.q - opening)) < 1e-9  # the parallelogram branch
    model = mujoco.MjModel.from_xml_path(str(XARM))
    data = mujoco.MjData(model)
    names = list(hand.model.names[1:])
    for joint, value in zip(names, a.q):
        data.qpos[model.joint(joint).qposadr[0]] = value
    mujoco.mj_forward(model, data)
    rows = data.efc_type == mujoco.mjtConstraint.mjCNSTR_EQUALITY
    assert rows.sum() == 7 and np.max(np.abs(data.efc_pos[rows])) < 1e-12
    assert data.actuator_length[0] == pytest.approx(opening, abs=1e-12)
    settled, length, qvel = _mujoco_settled(XARM, names, opening / 0.00333, 20000)
    assert qvel < 1e-6
    closed = hand.assemble({"fingers_actuator": length})
    e, J = hand.closure_residual(settled), hand.closure_jacobian(settled)
    free = hand.closure_model.split(("right_driver_joint",)).free_v
    sigma = np.linalg.svd(J[:, free], compute_uv=False)[-1]
    assert np.max(np.abs(closed - settled)) < np.linalg.norm(e) / sigma


@pytest.mark.parametrize("opening", [0.1, 0.45, 0.75])
def test_gripper_pad_freedom_is_held_by_its_spring_against_the_coupler_stop(gripper, opening):
    """Why the 2F-85 is compared given its couplers: it has DOF 3, the actuator and each finger's pad (the
    follower turning about the spring link, the coupler with it), which no closure fixes. MuJoCo's settled
    pose fixes each pad by statics: the spring link's spring (0.05 N m/rad towards 2.62 rad) does positive
    work along the pad freedom when the coupler angle grows, so it presses the coupler against its upper
    stop, 0 (measured 0.10, 0.072, 0.049 N m per rad of coupler). Both then determine the same pose: the
    actuator and the couplers at the stop (`test_gripper_agrees_with_mujocos_settled_pose`)."""
    assert gripper.home_mobility.dof == 3
    q = gripper.assemble({"fingers_actuator": opening, "right_coupler_joint": 0.0, "left_coupler_joint": 0.0})
    assert gripper.model.upperPositionLimit[gripper.q_index("right_coupler_joint")] == 0.0
    fixed = [gripper.v_index(j) for j in ("right_driver_joint", "left_coupler_joint")]
    rows = np.vstack([gripper.closure_jacobian(q), np.eye(gripper.model.nv)[fixed]])
    _, s, vt = np.linalg.svd(rows)
    assert rows.shape == (gripper.model.nv - 1, gripper.model.nv) and s[-1] > 1e-3  # full rank: one freedom left
    pad = vt[-1] / vt[-1][gripper.v_index("right_coupler_joint")]  # coupler angle growing at unit rate
    assert np.linalg.norm(rows @ pad) < 1e-9
    work = float(gripper.passive_forces(q, np.zeros(gripper.model.nv)) @ pad)
    assert work > 1e-2


def test_a_target_too_far_to_follow_is_not_followed():
    """A crank 1e300 rad (or NaN) from home: no continuation of 2e301 steps (it looped for ever), None at
    once; a target within MAX_STEPS steps is still followed."""
    m = mechkit.load("four_bar")
    split = m.closure_model.split(("crank",))
    for far in (1e300, np.nan, continuation.MAX_STEPS * continuation.MAX_STEP + 1.0):
        target = m.home_q.copy()
        target[m.q_index("crank")] += far
        assert continuation.continue_from(m.closure_model, m.closure_data, m.home_q, target, split, tol=1e-12) is None
    target = m.home_q.copy()
    target[m.q_index("crank")] += 2 * np.pi
    out = continuation.continue_from(m.closure_model, m.closure_data, m.home_q, target, split, tol=1e-12)
    turned = out.q - target  # a whole crank turn: back home, the coupler having turned once relative to it
    assert out is not None and np.max(np.abs(turned - 2 * np.pi * np.round(turned / (2 * np.pi)))) < 1e-9
