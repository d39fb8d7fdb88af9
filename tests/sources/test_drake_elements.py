"""`mechkit.sources.drake_elements`: Drake's ball constraint and Gazebo's joint close the four-bar as
`<mechkit:loop>` does (one freedom, one cut), with their frames where the files put them."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from tests_support import FIXTURES

import mechkit
from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.drake_elements import read_tool_closures, stiff_directions

CLOSURES = FIXTURES / "closures"


@pytest.mark.parametrize(
    "name, kind", [("four_bar_drake_ball.urdf", "spherical"), ("four_bar_gazebo_joint.urdf", "revolute")]
)
def test_the_four_bar_closed_by_another_tool_has_one_freedom_and_one_cut(name, kind):
    m = mechkit.load(CLOSURES / name)
    (cut,) = m.closures
    assert cut.kind == kind and m.home_mobility.dof == 1


def test_ball_constraints_in_a_xacro_macro_used_twice_close_both_legs():
    m = mechkit.load(CLOSURES / "leg_pair.urdf.xacro")
    assert m.home_mobility.dof == 1 and [c.kind for c in m.closures] == ["spherical", "spherical"]


def test_the_ball_s_frames_are_the_points_the_constraint_names():
    root = ET.parse(CLOSURES / "four_bar_drake_ball.urdf").getroot()
    (cut,) = read_tool_closures(root)
    origins = {
        j.find("child").get("link"): (j.find("parent").get("link"), j.find("origin").get("xyz"))
        for j in root.findall("joint")
    }
    assert origins[cut.frame_a][0] == "coupler_link" and origins[cut.frame_b][0] == "rocker_link"
    np.testing.assert_array_equal([float(v) for v in origins[cut.frame_a][1].split()], [0.28, 0, 0])
    np.testing.assert_array_equal([float(v) for v in origins[cut.frame_b][1].split()], [0.22, 0, 0])


def test_a_gazebo_joint_of_a_type_mechkit_cannot_cut_or_of_an_unknown_link_is_refused_by_name():
    robot = '<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="fixed"><parent link="a"/>'
    for inner, match in (
        ('<joint name="g" type="screw"><parent>a</parent><child>b</child></joint>', "gazebo/joint 'g'.*screw"),
        ('<joint name="g" type="ball"><parent>a</parent><child>c</child></joint>', "child 'c' is not a link"),
    ):
        root = ET.fromstring(f'{robot}<child link="b"/></joint><gazebo>{inner}</gazebo></robot>')
        with pytest.raises(MalformedDescription, match=match):
            read_tool_closures(root)


def _drake_holding_torque(path, q_of):
    """The crank torque holding the four-bar under gravity, from Drake's own parse of the file: gravity's
    generalised force, the ball's point Jacobians (its points P, Q as the fixture writes them) and a
    least-squares KKT solve [B, J^T] [tau; lambda] = -tau_g (ours)."""
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant
    from pydrake.multibody.tree import JacobianWrtVariable

    plant = MultibodyPlant(1e-3)
    Parser(plant).AddModels(str(path))
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("ground"))
    plant.Finalize()
    assert plant.num_constraints() == 1  # Drake read the ball constraint too
    ctx, world = plant.CreateDefaultContext(), plant.world_frame()
    for name in ("crank", "coupler", "rocker"):
        plant.GetJointByName(name).set_angle(ctx, q_of(name))
    jac = [
        plant.CalcJacobianTranslationalVelocity(
            ctx, JacobianWrtVariable.kV, plant.GetBodyByName(body).body_frame(), point, world, world
        )
        for body, point in (("coupler_link", [0.28, 0, 0]), ("rocker_link", [0.22, 0, 0]))
    ]
    select = np.zeros((plant.num_velocities(), 1))
    select[plant.GetJointByName("crank").velocity_start(), 0] = 1.0
    kkt = np.hstack([select, (jac[0] - jac[1]).T])
    return np.linalg.lstsq(kkt, -plant.CalcGravityGeneralizedForces(ctx), rcond=None)[0][0]


def _assembled(m, crank):
    """The assembly at `crank` (rad) reached from the one at 0 in small steps (one branch for both files)."""
    q = m.assemble({"crank": 0.0})
    for value in np.linspace(0.0, crank, 12)[1:]:
        q = m.assemble({"crank": value}, q)
    return q


@pytest.mark.parametrize("crank", [0.3, 1.0, 2.2])
def test_the_holding_torque_agrees_with_drake_and_with_the_gazebo_cut(crank):
    pytest.importorskip("pydrake")
    ball = mechkit.load(CLOSURES / "four_bar_drake_ball.urdf", actuated=["crank"])
    gazebo = mechkit.load(CLOSURES / "four_bar_gazebo_joint.urdf", actuated=["crank"])
    torques = []
    for m in (ball, gazebo):
        q = _assembled(m, crank)
        torques.append(m.inverse_dynamics(q, np.zeros(m.model.nv), np.zeros(m.model.nv)).efforts["crank"])
    q = _assembled(ball, crank)
    drake = _drake_holding_torque(
        CLOSURES / "four_bar_drake_ball.urdf", lambda n: q[ball.model.joints[ball.model.getJointId(n)].idx_q]
    )
    assert abs(torques[0] - drake) <= 1e-8 * abs(drake)
    assert abs(torques[1] - drake) <= 1e-8 * abs(drake)


def _drake_bushing_holding_torque(path, crank, q0, names=("crank", "coupler", "rocker"), ground="ground"):
    """Drake's crank torque holding the bushing four-bar: coupler and rocker settled by Newton (central
    differences) where gravity and the bushing balance, the crank held at `crank` (rad), from `q0`; `names`
    the crank, coupler and rocker joints, `ground` the link welded to the world (None: the file welds it)."""
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant
    from pydrake.multibody.tree import MultibodyForces

    plant = MultibodyPlant(0.0)
    Parser(plant).AddModels(str(path))
    if ground is not None:
        plant.WeldFrames(plant.world_frame(), plant.GetFrameByName(ground))
    plant.Finalize()
    ctx = plant.CreateDefaultContext()
    joints = [plant.GetJointByName(n) for n in names]
    rows = [j.velocity_start() for j in joints]

    def forces(free):
        for joint, value in zip(joints, (crank, *free)):
            joint.set_angle(ctx, value)
        applied = MultibodyForces(plant)
        plant.CalcForceElementsContribution(ctx, applied)
        return plant.CalcGeneralizedForces(ctx, applied)[rows]

    free = np.asarray(q0, float)
    for _ in range(8):
        jac = np.column_stack([(forces(free + 1e-7 * e)[1:] - forces(free - 1e-7 * e)[1:]) / 2e-7 for e in np.eye(2)])
        free = free - np.linalg.solve(jac, forces(free)[1:])
    assert np.abs(forces(free)[1:]).max() < 1e-8
    return -forces(free)[0]


def _stiffer(tmp_path, factor):
    """The bushing four-bar with its stiff directions `factor` times stiffer (its free one still 0)."""
    text = (CLOSURES / "four_bar_drake_bushing.urdf").read_text()
    text = text.replace('"1e4 0 1e4"', f'"{1e4 * factor} 0 {1e4 * factor}"')
    text = text.replace('"1e6 1e6 1e6"', " ".join([f'"{1e6 * factor}'] + [f"{1e6 * factor}"] * 2) + '"')
    path = tmp_path / f"stiffer_{factor}.urdf"
    path.write_text(text)
    return path


def test_the_bushing_read_as_a_pin_agrees_with_drake_s_compliant_bushing_to_its_compliance(tmp_path):
    """Read rigid, the pin's holding torque differs from Drake's compliant equilibrium by the bushing's
    deflection (~1e-6 rad here, 1e6 N/m and 1e4 N m/rad): under 1e-5 relative, and a hundred times
    stiffer bushing brings Drake at least thirty times closer (the gap is the compliance, not a mistake)."""
    pytest.importorskip("pydrake")
    gaps = []
    for path in (CLOSURES / "four_bar_drake_bushing.urdf", _stiffer(tmp_path, 100)):
        m = mechkit.load(path, actuated=["crank"])
        (cut,) = m.closures
        assert (cut.kind, m.home_mobility.dof) == ("revolute", 1)
        q = _assembled(m, 1.0)
        ours = m.inverse_dynamics(q, np.zeros(m.model.nv), np.zeros(m.model.nv)).efforts["crank"]
        start = [q[m.model.joints[m.model.getJointId(n)].idx_q] for n in ("coupler", "rocker")]
        drake = _drake_bushing_holding_torque(path, 1.0, start)
        gaps.append(abs(ours - drake) / abs(drake))
    assert gaps[0] < 1e-5 and gaps[1] < gaps[0] / 30, gaps


@pytest.mark.parametrize(
    "torque, force, kind, axis",
    [
        ([1e4, 0, 1e4], [1e6] * 3, "revolute", [0, 1, 0]),
        ([0, 0, 0], [1e6] * 3, "spherical", None),
        ([1e4] * 3, [1e6] * 3, "weld", None),
        ([1e4] * 3, [1e6, 1e6, 1.0], "prismatic", [0, 0, 1]),
        ([0, 0, 1e4], [1e6] * 3, "", None),
        ([1e4] * 3, [0, 0, 0], "", None),
    ],
)
def test_a_bushing_s_stiff_directions_make_its_joint(torque, force, kind, axis):
    got_kind, got_axis = stiff_directions(np.array(torque, float), np.array(force, float))
    assert got_kind == kind and (got_axis is None if axis is None else np.array_equal(got_axis, axis))


def test_an_undeclared_world_is_the_ground(tmp_path):
    """The Drake-ball four-bar with its ground renamed `world` and not declared (as Drake and Gazebo
    allow) is the same mechanism: one freedom, the same holding torque."""
    text = (CLOSURES / "four_bar_drake_ball.urdf").read_text()
    path = tmp_path / "world.urdf"
    path.write_text(text.replace('<link name="ground"/>', "").replace('link="ground"', 'link="world"'))
    torques = []
    for source in (path, CLOSURES / "four_bar_drake_ball.urdf"):
        m = mechkit.load(source, actuated=["crank"])
        assert m.home_mobility.dof == 1
        q = _assembled(m, 1.0)
        torques.append(m.inverse_dynamics(q, np.zeros(m.model.nv), np.zeros(m.model.nv)).efforts["crank"])
    assert abs(torques[0] - torques[1]) <= 1e-12 * abs(torques[1])


@pytest.mark.parametrize("motor", [-0.5, 0.4, 1.2])
def test_the_sdformat_bushing_read_rigid_holds_as_the_pin_it_replaces(motor):
    """four_bar_drake_bushing.sdf is four_bar_gearbox.sdf with its cut pin_C replaced by Drake's bushing at C,
    free about y: read as the revolute cut it stands for, one freedom and the same motor holding torque."""
    torques = []
    for path in (CLOSURES / "four_bar_drake_bushing.sdf", FIXTURES / "field" / "sdf" / "four_bar_gearbox.sdf"):
        m = mechkit.load(path)
        assert m.home_mobility.dof == 1 and [c.kind for c in m.closures] == ["revolute"]
        q = m.assemble({"motor": motor})
        torques.append(m.inverse_dynamics(q, np.zeros(m.model.nv), np.zeros(m.model.nv)).efforts["motor"])
    assert abs(torques[0] - torques[1]) <= 1e-9 * abs(torques[1])


def test_the_sdformat_bushing_agrees_with_drake_loading_the_file_to_its_compliance(tmp_path):
    """The bushing SDF without its gearbox (Drake reads no gearbox joint): mechkit's rigid holding torque at
    crank 0.5 rad differs from Drake's compliant equilibrium by the bushing's compliance (1.4e-4 relative
    measured, the rocker's spring loading the bushing), and a hundred times stiffer bushing brings Drake a
    hundred times closer (1.4e-6 measured): the gap is the compliance, not a misreading."""
    pytest.importorskip("pydrake")
    text = (CLOSURES / "four_bar_drake_bushing.sdf").read_text()
    text = re.sub(r'<joint name="(motor|gear)".*?</joint>|<link name="rotor">.*?</link>', "", text, flags=re.DOTALL)
    names, gaps = ("crank_joint", "coupler_joint", "rocker_joint"), []
    for factor in (1, 100):
        path = tmp_path / f"four_bar_bushing_{factor}.sdf"
        path.write_text(
            text.replace("1e4 0 1e4", f"{1e4 * factor} 0 {1e4 * factor}").replace(
                "1e6 1e6 1e6", " ".join([str(1e6 * factor)] * 3)
            )
        )
        m = mechkit.load(path, actuated=["crank_joint"])
        q = m.assemble({"crank_joint": 0.5})
        ours = m.inverse_dynamics(q, np.zeros(m.model.nv), np.zeros(m.model.nv)).efforts["crank_joint"]
        start = [q[m.model.joints[m.model.getJointId(n)].idx_q] for n in names[1:]]
        theirs = _drake_bushing_holding_torque(path, 0.5, start, names, None)
        gaps.append(abs(ours - theirs) / abs(theirs))
    assert gaps[0] < 5e-4 and gaps[1] < gaps[0] / 30, gaps


@pytest.mark.parametrize("motor", [-0.5, 0.4, 1.2])
def test_the_sdformat_ball_constraint_holds_as_the_pin_it_replaces(motor):
    """four_bar_drake_ball.sdf is four_bar_gearbox.sdf with its cut pin_C replaced by Drake's ball
    constraint at C: one freedom, and the motor's holding torque under gravity is the same."""
    torques = []
    for path in (CLOSURES / "four_bar_drake_ball.sdf", FIXTURES / "field" / "sdf" / "four_bar_gearbox.sdf"):
        m = mechkit.load(path)
        assert m.home_mobility.dof == 1 and len(m.closures) == 1
        q = m.assemble({"motor": motor})
        torques.append(m.inverse_dynamics(q, np.zeros(m.model.nv), np.zeros(m.model.nv)).efforts["motor"])
    assert abs(torques[0] - torques[1]) <= 1e-9 * abs(torques[1])


STRANDBEEST = FIXTURES / "drake" / "strandbeest"


def _welded_strandbeest(tmp_path, name):
    """Drake's Strandbeest rendered by mechkit's xacro reader, its crossbar welded 1 m above the world
    (Drake leaves it free)."""
    from mechkit.sources.xacro_file import render_urdf

    text = render_urdf(STRANDBEEST / name, {}).replace(
        "</robot>",
        '<joint name="crossbar_weld" type="fixed"><parent link="world"/><child link="crossbar"/>'
        '<origin xyz="0 0 1"/></joint></robot>',
    )
    path = tmp_path / f"{name}.urdf"
    path.write_text(text)
    return path


def test_drake_s_strandbeest_as_written_floats_its_crossbar_as_drake_does(tmp_path):
    """The file as Drake ships it: the floor welded to `world`, the crossbar held by no joint. Drake floats
    a body no joint holds; so does mechkit (it refused the second root): as many velocities as Drake's plant,
    DOF 7 (the crossbar's 6 and the crank); fixing the crossbar gives the welded Strandbeest's crank torque."""
    pytest.importorskip("pydrake")
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    from mechkit.sources.xacro_file import render_urdf

    path = tmp_path / "strandbeest.urdf"
    path.write_text(render_urdf(STRANDBEEST / "StrandbeestConstraints.urdf.xacro", {}))
    free = mechkit.load(path)
    plant = MultibodyPlant(0.0)
    Parser(plant).AddModels(str(path))
    plant.Finalize()
    assert free.model.nv == plant.num_velocities() == 79 and free.home_mobility.dof == 7
    fixed, welded = (
        mechkit.load(path, fix=["crossbar"]),
        mechkit.load(_welded_strandbeest(tmp_path, "StrandbeestConstraints.urdf.xacro")),
    )
    assert fixed.home_mobility.dof == 1
    torques = []
    for m in (fixed, welded):
        q = m.assemble({"joint_crossbar_crank": 0.4})
        torques.append(
            m.inverse_dynamics(q, np.zeros(m.model.nv), np.zeros(m.model.nv)).efforts["joint_crossbar_crank"]
        )
    assert abs(torques[0]) > 1e-3 and torques[0] == pytest.approx(torques[1], rel=1e-9)


@pytest.mark.parametrize(
    "name, kind", [("StrandbeestConstraints.urdf.xacro", "spherical"), ("StrandbeestBushings.urdf.xacro", "revolute")]
)
def test_drake_s_strandbeest_welded_has_one_freedom_and_36_cuts(tmp_path, name, kind):
    m = mechkit.load(_welded_strandbeest(tmp_path, name))
    assert m.home_mobility.dof == 1 and len(m.closures) == 36 and {c.kind for c in m.closures} == {kind}


def test_the_strandbeest_s_crank_holding_torque_agrees_with_drake(tmp_path):
    """Drake parses the same rendered file (its 36 ball constraints); the crank torque holding the
    welded Strandbeest under gravity from Drake's gravity force and ball point Jacobians (a KKT solve,
    ours) equals mechkit's to 1e-8 relative at three crank angles reached by continuation."""
    pytest.importorskip("pydrake")
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant
    from pydrake.multibody.tree import JacobianWrtVariable

    path = _welded_strandbeest(tmp_path, "StrandbeestConstraints.urdf.xacro")
    m = mechkit.load(path)
    plant = MultibodyPlant(1e-3)
    Parser(plant).AddModels(str(path))
    plant.Finalize()
    assert plant.num_constraints() == 36
    ctx, world, drake = plant.CreateDefaultContext(), plant.world_frame(), "{http://drake.mit.edu}"
    balls = [
        [
            (
                e.find(f"{drake}ball_constraint_body_{s}").get("name"),
                e.find(f"{drake}ball_constraint_p_{p}").get("value"),
            )
            for s, p in (("A", "AP"), ("B", "BQ"))
        ]
        for e in ET.parse(path).getroot().iter(f"{drake}ball_constraint")
    ]
    select = np.zeros((plant.num_velocities(), 1))
    select[plant.GetJointByName("joint_crossbar_crank").velocity_start(), 0] = 1.0
    q, compared = m.assemble({"joint_crossbar_crank": 0.0}), 0
    for crank in np.arange(0.1, 1.01, 0.1):
        q = m.assemble({"joint_crossbar_crank": crank}, q)
        if not np.any(np.isclose(crank, [0.3, 0.6, 1.0])):
            continue
        ours = m.inverse_dynamics(q, np.zeros(m.model.nv), np.zeros(m.model.nv)).efforts["joint_crossbar_crank"]
        for index in plant.GetJointIndices():
            joint = plant.get_joint(index)
            if joint.num_positions() == 1:
                mj = m.model.joints[m.model.getJointId(joint.name())]
                value = q[mj.idx_q : mj.idx_q + mj.nq]
                joint.set_angle(ctx, value[0] if mj.nq == 1 else np.arctan2(value[1], value[0]))
        rows = [
            sign
            * plant.CalcJacobianTranslationalVelocity(
                ctx,
                JacobianWrtVariable.kV,
                plant.GetBodyByName(body).body_frame(),
                np.fromstring(p, sep=" "),
                world,
                world,
            )
            for ball in balls
            for sign, (body, p) in zip((1.0, -1.0), ball)
        ]
        jac = np.vstack([rows[k] + rows[k + 1] for k in range(0, len(rows), 2)])
        kkt = np.hstack([select, jac.T])
        theirs = np.linalg.lstsq(kkt, -plant.CalcGravityGeneralizedForces(ctx), rcond=None)[0][0]
        assert abs(ours - theirs) <= 1e-8 * abs(theirs), (crank, ours, theirs)
        compared += 1
    assert compared == 3


def _drake_compliant_crank_torque(path, crank_values):
    """Drake's crank torque holding the bushing Strandbeest (same file): every other joint settled by
    Newton (central differences) where gravity and the 36 bushings balance; `crank_values` maps a joint
    name to its starting angle (rad), the crank's held."""
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant
    from pydrake.multibody.tree import MultibodyForces

    plant = MultibodyPlant(0.0)
    Parser(plant).AddModels(str(path))
    plant.Finalize()
    ctx = plant.CreateDefaultContext()
    joints = [plant.get_joint(i) for i in plant.GetJointIndices() if plant.get_joint(i).num_positions() == 1]
    rows = np.array([j.velocity_start() for j in joints])
    crank = [j.name() for j in joints].index("joint_crossbar_crank")
    free = [k for k in range(len(joints)) if k != crank]

    def forces(x):
        for joint, value in zip(joints, x):
            joint.set_angle(ctx, value)
        applied = MultibodyForces(plant)
        plant.CalcForceElementsContribution(ctx, applied)
        return plant.CalcGeneralizedForces(ctx, applied)[rows]

    x = np.array([crank_values[j.name()] for j in joints])
    for _ in range(5):
        steps = np.eye(len(x))[free] * 1e-7
        jac = np.column_stack([(forces(x + e)[free] - forces(x - e)[free]) / 2e-7 for e in steps])
        x[free] += np.linalg.lstsq(jac, -forces(x)[free], rcond=None)[0]
    assert np.abs(forces(x)[free]).max() < 1e-6
    return -forces(x)[crank]


def test_the_bushing_strandbeest_read_as_pins_agrees_with_drake_to_the_bushings_compliance(tmp_path):
    """Read as pins, the welded bushing Strandbeest's crank holding torque at 1 rad differs from Drake's
    compliant equilibrium by the bushings' compliance, and a hundred times stiffer bushings bring Drake about
    a hundred times closer. On the assembly inside the file's joint limits (`core.seek_inside_limits`) with
    Drake's 2e4 N/m and 2e4 N m/rad: 0.73 relative, 5.0e-3 stiffer (1/146; on the branch Newton found
    from the joints' zero, outside the limits: 1.5e-2 and 1.6e-4): the legs sit where the torque is more
    sensitive to the bushings' deflection, and the gap scales with the compliance."""
    pytest.importorskip("pydrake")
    path = _welded_strandbeest(tmp_path, "StrandbeestBushings.urdf.xacro")
    stiffer = tmp_path / "stiffer.urdf"
    stiffer.write_text(
        path.read_text()
        .replace('value="20000 20000 0"', 'value="2000000 2000000 0"')
        .replace('value="20000 20000 20000"', 'value="2000000 2000000 2000000"')
    )
    gaps = []
    for source in (path, stiffer):
        m = mechkit.load(source)
        q = m.assemble({"joint_crossbar_crank": 0.0})
        for crank in np.linspace(0.1, 1.0, 10):
            q = m.assemble({"joint_crossbar_crank": crank}, q)
        ours = m.inverse_dynamics(q, np.zeros(m.model.nv), np.zeros(m.model.nv)).efforts["joint_crossbar_crank"]
        angles = {}
        for name in m.model.names[1:]:
            mj = m.model.joints[m.model.getJointId(name)]
            value = q[mj.idx_q : mj.idx_q + mj.nq]
            angles[name] = value[0] if mj.nq == 1 else np.arctan2(value[1], value[0])
        theirs = _drake_compliant_crank_torque(source, angles)
        gaps.append(abs(ours - theirs) / abs(theirs))
    assert gaps[0] < 1.0 and gaps[1] < 1e-2 and gaps[1] < gaps[0] / 50, gaps


@pytest.mark.parametrize("kind", ["universal", "revolute2"])
def test_a_gazebo_universal_joint_is_a_hooke_cut_holding_as_the_pin(tmp_path, kind):
    """four_bar_gazebo_joint.urdf with its pin C a universal (or revolute2) joint, axis2 along the coupler's
    x: a Hooke cut; the planar loop leaves its second axis no motion, so DOF 1 and the crank torque holding
    it at 1 rad is the pin's (1e-9). Axes not perpendicular are refused by name."""
    text = (CLOSURES / "four_bar_gazebo_joint.urdf").read_text()
    old = '<joint name="C" type="revolute">'
    path = tmp_path / f"{kind}.urdf"
    path.write_text(
        text.replace(old, f'<joint name="C" type="{kind}">').replace(
            "<axis><xyz>0 -1 0</xyz></axis>", "<axis><xyz>0 -1 0</xyz></axis><axis2><xyz>1 0 0</xyz></axis2>"
        )
    )
    torques = []
    for source in (path, CLOSURES / "four_bar_gazebo_joint.urdf"):
        m = mechkit.load(source, actuated=["crank"])
        assert m.home_mobility.dof == 1
        q = _assembled(m, 1.0)
        torques.append(m.inverse_dynamics(q, np.zeros(m.model.nv), np.zeros(m.model.nv)).efforts["crank"])
    assert [c.kind for c in mechkit.load(path).closures] == ["hooke"]
    assert abs(torques[0] - torques[1]) <= 1e-9 * abs(torques[1])
    path.write_text(path.read_text().replace("<axis2><xyz>1 0 0</xyz>", "<axis2><xyz>1 -1 0</xyz>"))
    with pytest.raises(MalformedDescription, match="gazebo/joint 'C'.*not perpendicular"):
        mechkit.load(path)
