"""Ten-bar (patent CN105975733): design, mobility, kinematics and dynamics two ways, reactions three ways."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechkit import core
from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.mechanisms.ten_bar import SPEC
from mechkit.mechanisms.ten_bar import checks as tc
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar import kinematics as tk
from mechkit.mechanisms.ten_bar import lagrange_model as lm
from mechkit.mechanisms.ten_bar import limits as tl
from mechkit.mechanisms.ten_bar import params as tp
from mechkit.mechanisms.ten_bar import soc as ts


@pytest.fixture(scope="module")
def mech(load_cached):
    return load_cached("ten_bar")


@pytest.fixture(scope="module")
def stretch(mech):
    """The first 0.1 s of the deployment (spring release) by both dynamics routes, dt = 5 ms."""
    pin_run = td.PinocchioDeployment(mech)
    lag_run = td.LagrangeJointDeployment(mech.params)
    a = td.deploy(pin_run, mech.home_q, 0.005, 0.1)
    b = td.deploy(lag_run, pin_run.joint_angles(mech.home_q), 0.005, 0.1)
    return a, b


def mid_state(mech, rates=(0.05, -0.1, 0.2)):
    p = mech.params
    q = tk.full_solve(mech, {"R1": 0.7, "R3": -1.2, "R5": -0.3}, mech.home_q)
    v = mech.velocities(q, dict(zip(("R1", "R3", "R5"), rates)), inputs=("R1", "R3", "R5"))
    return 0.37 * p.deploy_time, q, v


# ------------------------------------------------------------------ design and description
@pytest.mark.parametrize(
    "change, name",
    [({"l27": 0.1}, "l27/l67"), ({"spring_damping": -1.0}, "spring_damping"), ({"l48": -0.9}, "l48")],
)
def test_bad_parameters_are_named(change, name):
    with pytest.raises(InvalidParameters, match=name):
        tp.TenBarParams(**change)


def test_topology_is_the_patents(mech):
    assert mech.model.nv == 9 and mech.model.njoints - 1 == 9  # 9 moving links on 9 tree joints
    assert sorted(c.name for c in mech.closures) == sorted(geo.CUT_JOINTS)
    assert all(c.kind == "revolute" and c.rows == "planar" for c in mech.closures)
    pairs = list(mech.model.names[1:]) + [c.name for c in mech.closures]
    assert sorted(pairs) == sorted(geo.PAIRS) and len(pairs) == 12
    assert mech.actuated == ("R1", "R3")
    gruebler = 3 * 9 - 2 * 12
    assert gruebler == mech.spec.gruebler_dof == mech.mobility().dof == 3
    assert mech.mobility().redundant == 0


def test_each_unit_has_the_patents_mobility(mech):
    reduction = tk.DimensionReduction(mech)
    dof = {}
    for unit in reduction.units:
        q = np.array([mech.home_q[mech.q_index(j)] for j in unit.model.names[1:]])
        dof[unit.unit.name] = core.mobility(unit.closure_model, unit.closure_data, q).dof
    # five-bar 2 (the patent's), four-bar 1 on top of l123 (R2 given), six-bar 2 (R2 and the R3 motor)
    assert dof == {"five_bar": 2, "four_bar": 1, "six_bar": 2}


def test_mass_properties_match_the_urdf(mech):
    props = geo.mass_properties(mech.params)
    child = {h.child: h.name for h in geo.hinges(mech.params)[:9]}
    for body, (mass, com, inertia) in props.items():
        I = mech.model.inertias[mech.model.getJointId(child[body])]
        assert I.mass == pytest.approx(mass, rel=1e-12)
        assert np.allclose(I.lever[[0, 2]], com, atol=1e-12)
        assert I.inertia[1, 1] == pytest.approx(inertia, rel=1e-12)
    panels = props["l34"][0]
    assert panels == pytest.approx(2.5 * 1.2 * 1.0)  # 1.2 m x 1.0 m at 2.5 kg/m^2


def test_spring_is_read_from_the_urdf(mech):
    assert tp.spring_from_urdf(mech.urdf) == tp.spring(mech.params)


def test_every_loop_closes_for_every_input():
    p = tp.TenBarParams()
    grid = np.linspace(-math.pi, math.pi, 13)
    worst = min(min(geo.pose(p, a, b, c).margins.values()) for a in grid for b in grid for c in grid)
    assert worst > 0.4  # sine of the angle at each closing hinge: far from every dead-centre pose


def test_stowed_and_deployed_poses_and_the_wall():
    p = tp.TenBarParams()
    stowed = geo.stowed_pose(p)
    assert np.allclose(geo.unit(stowed.angles["l123"]), [0, 1]) and np.allclose(
        geo.unit(stowed.angles["l34"]), [0, -1]
    )
    deployed = geo.pose(p, tp.DEPLOYED["R1"], tp.DEPLOYED["R3"], 0.0)
    R2, R3, R4 = (deployed.points[k] for k in ("R2", "R3", "R4"))
    cross = (R3 - R2)[0] * (R4 - R3)[1] - (R3 - R2)[1] * (R4 - R3)[0]
    assert abs(cross) < 1e-15 and (R3 - R2) @ (R4 - R3) > 0  # collinear, same direction
    assert np.allclose((R4 - R2) / np.linalg.norm(R4 - R2), [1, 0])  # perpendicular to the wall x = 0
    for s in np.linspace(0, 1, 11):  # every hinge and panel end outside the wall over the deployment
        for rocker in np.radians(np.arange(-60, 11, 10)):
            pose = geo.pose(p, math.pi / 2 * (1 - s), -math.pi * (1 - s), rocker)
            assert min(x[0] for k, x in pose.points.items() if k not in ("R1", "R5")) > 0.03
            tip = pose.points["R3"] + p.panel2 * geo.unit(pose.angles["l34"])
            assert tip[0] > 0


# ------------------------------------------------------------------ kinematics two ways
def test_full_closure_and_dimension_reduction_agree(mech):
    worst = tc.kinematics_disagreement(mech, tc.nominal_inputs(mech.params, 21))
    assert worst["full_vs_reduction"] < 1e-10
    assert worst["full_vs_closed_form"] < 1e-10


def test_the_motors_alone_leave_the_passive_motion_free(mech):
    split = tl.kinematic_split(mech, mech.home_q)
    assert split.nullity == 1 and split.five_bar_nullity == 1
    assert abs(split.direction[mech.v_index("R5")]) > 1e-3  # the free motion moves the spring's rocker
    with pytest.raises(SingularConfiguration):
        mech.velocities(mech.home_q, {"R1": 0.1, "R3": 0.2})


# ------------------------------------------------------------------ dynamics two ways
@pytest.mark.parametrize("rates", [(0.0, 0.0, 0.0), (0.05, -0.1, 0.2), (-0.3, 0.4, -2.0)])
def test_constrained_aba_equals_the_lagrange_first_kind(mech, rates):
    t, q, v = mid_state(mech, rates)
    a, u, power = td.PinocchioDeployment(mech).rhs(t, q, v)
    lag = td.LagrangeJointDeployment(mech.params)
    aL, uL, powerL = lag.rhs(
        t,
        lag.joint_angles(q[[mech.q_index(j) for j in td.JOINT_ORDER]]),
        v[[mech.v_index(j) for j in td.JOINT_ORDER]],
    )
    order = [mech.v_index(j) for j in td.JOINT_ORDER]
    assert np.max(np.abs(a[order] - aL)) < 1e-9 * max(1.0, np.max(np.abs(aL)))
    assert np.allclose(u, uL, rtol=1e-10, atol=1e-10) and power == pytest.approx(powerL, rel=1e-10, abs=1e-12)


def test_reactions_three_ways(mech):
    t, q, v = mid_state(mech)
    results = tc.reactions_three_ways(mech, t, q, v)
    assert tc.reaction_disagreement(results) < 1e-8
    inv = mech.inverse_dynamics(q, v, td.PinocchioDeployment(mech).rhs(t, q, v)[0])  # the R5 spring: the mechanism's
    for motor in tp.MOTORS:  # the motor torque is the reaction moment about the axis (-y)
        assert inv.reactions[motor].wrench[4] == pytest.approx(-inv.efforts[motor], rel=1e-10)
    for pair in geo.PAIRS:  # planar pins: in-plane forces and the axis moment are determinate
        assert list(inv.reactions[pair].determinate) == [True, False, True, False, True, False]
    qL, vL = td.lagrange_state(mech.params, q, v, mech)
    L = lm.lagrange_linkage(mech.params)
    _, _, soc = ts.solve(L, qL, vL, L.solve(qL, vL, tp.motor_law(mech.params, t)[2]).qdd)
    assert max(soc.consistency.values()) < 1e-10  # incl. the hub: the passive equation of motion holds


def test_deployment_stretch_two_ways(stretch):
    a, b = stretch
    assert max(a.residual.max(), b.residual.max()) < 1e-9
    assert np.max(np.abs(a.angles - b.angles)) < 1e-8
    assert np.allclose(a.torques, b.torques, rtol=1e-8, atol=1e-8)
    assert a.energy_error < 1e-3 and b.energy_error < 1e-3  # J, against ~60 J of energy exchanged
    assert abs(a.angles[-1, 5] - a.angles[0, 5]) > 0.5  # the spring has swung the rocker


def test_lagrange_in_its_own_coordinates_converges_at_fourth_order(mech):
    pin_run, lag_run = td.PinocchioDeployment(mech), td.LagrangeDeployment(mech.params)
    qL = lm.lagrange_coordinates(mech.params, geo.stowed_pose(mech.params))
    diffs = []
    for dt in (0.02, 0.01):
        a = td.deploy(pin_run, mech.home_q, dt, 0.2)
        b = td.deploy(lag_run, qL, dt, 0.2)
        diffs.append(np.max(np.abs(a.angles - b.angles)))
    assert math.log2(diffs[0] / diffs[1]) > 3.5


def test_the_dynamics_decides_the_passive_dof(mech, load_cached):
    stiff = load_cached("ten_bar", spring_stiffness=8.0, spring_preload=10.8)
    a = td.deploy(td.PinocchioDeployment(mech), mech.home_q, 0.01, 0.2)
    b = td.deploy(td.PinocchioDeployment(stiff), stiff.home_q, 0.01, 0.2)
    motors = [td.JOINT_ORDER.index(m) for m in tp.MOTORS]
    assert np.allclose(a.angles[:, motors], b.angles[:, motors], atol=1e-12)
    assert abs(a.angles[-1, 5] - b.angles[-1, 5]) > 0.05


def test_stabilisation_bounds_the_drift(mech):
    """Over the drift study's 5 s at 20 ms (the simulator's fifth-order steps: after 0.5 s the free drift
    is still within 1.3 times Baumgarte's, which its transient at the spring release sets), the free
    drift grows, Baumgarte's stays bounded, projection removes it."""
    free = tl.drift(mech, 5.0, 0.02, None, project=False).residual.max()
    baumgarte = tl.drift(mech, 5.0, 0.02, (100.0, 20.0), project=False).residual.max()
    projected = tl.drift(mech, 5.0, 0.02, None, project=True).residual.max()
    assert free > 10 * baumgarte and baumgarte > 1e3 * projected and projected < 1e-12


def test_report_rows(mech):
    rows = SPEC.self_checks(mech)
    assert all(value < 1e-8 for value in rows.values()), rows


@pytest.mark.slow
def test_full_deployment(mech):
    pin_run = td.PinocchioDeployment(mech)
    a = td.deploy(pin_run, mech.home_q, 0.005)
    b = td.deploy(td.LagrangeJointDeployment(mech.params), pin_run.joint_angles(mech.home_q), 0.005)
    assert a.residual.max() < 1e-9 and b.residual.max() < 1e-9
    assert np.max(np.abs(a.angles - b.angles)) < 1e-8
    motors = [td.JOINT_ORDER.index(m) for m in tp.MOTORS]
    assert np.allclose(a.angles[-1, motors], [tp.DEPLOYED[m] for m in tp.MOTORS], atol=1e-12)
    margins = tl.loop_margins(mech.params, a.angles[::10])
    assert min(m.min() for m in margins.values()) > 0.6
    for k in (len(a.t) // 4, len(a.t) // 2, 3 * len(a.t) // 4):
        assert tc.reaction_disagreement(tc.reactions_three_ways(mech, a.t[k], a.q[k], a.v[k])) < 1e-8


def test_bench_runs_every_route(mech):
    """`mechkit bench ten_bar` (the routes of the former tools/ten_bar_bench.py): constrained ABA
    (pin.constraintDynamics), the Lagrange first kind forward and inverse, SOC virtual work, the
    dimension reduction and the closed form, each timed and agreeing with the references."""
    from mechkit.bench.run import bench_mechanism

    b = bench_mechanism(mech, quick=True, with_peers=False)
    by = {r.method.name: r for r in b.rows}
    for name in ("raw pin.constraintDynamics (mu=1e-9)", "constrained RNEA, no determinacy",
                 *(m.label for m in mech.spec.bench_methods)):
        assert by[name].outcome == "ok" and by[name].median_s > 0, name
    for m in mech.spec.bench_methods:
        assert by[m.label].error < 1e-9, m.label
    assert {m.quantity for m in mech.spec.bench_methods} == {"assembly", "forward_dynamics", "inverse_dynamics"}


def test_deployment_law_is_the_deployment_scene(mech):
    """`SPEC.motion_laws["deploy"]`: the motors and the rocker along the deployment scene's poses, each a
    warm start, at the scene's times."""
    from mechkit import motion
    from mechkit.mechanisms.ten_bar.scenes import deployment_poses, deployment_times

    law = motion.from_law(mech, "deploy", 11)
    poses = np.array(deployment_poses(mech, 11))
    assert law.names == ("R1", "R3", "R5")
    assert np.array_equal(law.guesses, poses) and np.array_equal(law.t, deployment_times(mech, 11))
    assert np.array_equal(law.values, poses[:, [mech.q_index(j) for j in law.names]])


def test_deployment_metric_through_the_sweep(mech):
    """The sweep reads the ten-bar's `deployment` metric from its spec: the largest motor torque of the
    deployment at the scene's step (R1, about 86 N m at 5 ms) and a latch speed."""
    from mechkit.sweep.specific import resolve

    metrics = {m.name: m for m in resolve("ten_bar", None)}
    assert list(metrics) == ["assembles", "branch", "deployment"]
    values = metrics["deployment"].fn(mech, None)
    assert set(values) == set(metrics["deployment"].columns(mech)) == {"max_motor_torque", "latch_speed"}
    assert 80.0 < values["max_motor_torque"] < 95.0 and 0.0 <= values["latch_speed"] < 1.0


@pytest.mark.slow
def test_cross_checks_short(mech):
    """The deployment's cross-checks over 0.2 s (moved from test_ten_bar_tools.py)."""
    from mechkit.mechanisms.ten_bar.studies import cross_check_lines, cross_checks

    c = cross_checks(mech, t_end=0.2, samples=3)
    assert "worst relative difference" in "\n".join(cross_check_lines(c))
    assert c.reaction_disagreement < 1e-12


@pytest.mark.slow
def test_deployment_figures_written(mech, tmp_path):
    """The deployment's five figures over 0.5 s (moved from test_ten_bar_tools.py)."""
    from mechkit.mechanisms.ten_bar.figures import deployment_figures
    from mechkit.mechanisms.ten_bar.studies import deployment

    deployment_figures(deployment(mech, t_end=0.5), tmp_path)
    for name in ("poses", "angles", "torques", "supports", "drift"):
        assert (tmp_path / f"ten_bar_{name}.png").stat().st_size > 10_000
