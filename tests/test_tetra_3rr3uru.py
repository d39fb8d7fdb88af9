"""3RR-3URU unit: the paper's analytic kinematics (eq. 6-13, drive laws), the model's mobility and
fold, and SOC virtual work against Pinocchio's constrained RNEA."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.base.spatial import rot_x, rot_y, rot_z
from mechkit.mechanisms.tetra_3rr3uru import TetraParams, soc
from mechkit.mechanisms.truss.drives import drive_state
from mechkit.mechanisms.truss.fold import fold
from mechkit.mechanisms.truss.geometry import (
    DEG,
    GAMMA0,
    R_B0_ANGLES,
    TrussGeometry,
    euler_xyz,
    rot_axis,
    rpy_angles,
)
from mechkit.mechanisms.truss.joint_state import web_joint_motion
from mechkit.mechanisms.truss.nodes import node_positions

GEOMETRY = TrussGeometry(0.590, 0.2504, 0.250)
TIMES = (0.0, 37.0, 100.0, 163.0, 200.0)


@pytest.mark.parametrize("t", TIMES)
def test_eq6_web_rods_equal_and_fold_synchronous(t):
    s = drive_state(t)
    p = GEOMETRY.node_positions(s.alpha, s.gamma)
    for node in ("A", "B", "E"):
        assert np.linalg.norm(p["H"] - p[node]) == pytest.approx(0.590, abs=1e-14)
    ab, ae, be = (np.linalg.norm(p[x] - p[y]) for x, y in (("A", "B"), ("A", "E"), ("B", "E")))
    assert ab == pytest.approx(ae, abs=1e-14)
    assert be / ab == pytest.approx(0.250 / 0.2504, rel=1e-13)  # beta makes every link fold alike
    xi = 23.171 * DEG + 0.25 * DEG * t
    assert ab / 2 == pytest.approx(0.2504 * np.cos(xi), rel=5e-4)  # 0.490 = l1 / (L cos beta), printed to 3 digits


@pytest.mark.parametrize("t", TIMES)
def test_eq8_units_are_rotated_copies(t):
    s = drive_state(t)
    p = GEOMETRY.node_positions(s.alpha, s.gamma)
    for a, b in (("B", "C"), ("E", "F"), ("H", "J")):
        np.testing.assert_allclose(p[b], rot_z(-2 * np.pi / 3) @ p[a], atol=1e-15)
    for a, b in (("B", "D"), ("E", "G"), ("H", "I")):
        np.testing.assert_allclose(p[b], rot_z(2 * np.pi / 3) @ p[a], atol=1e-15)


def test_gamma_law_sign_reading_gives_the_printed_gamma0():
    assert drive_state(0.0).gamma == pytest.approx(GAMMA0, abs=5e-4 * DEG)  # printed to 0.001 deg
    gammas = [drive_state(t).gamma for t in np.linspace(0, 200, 41)]
    assert max(gammas) < 0.0


@pytest.mark.parametrize("t", (1.0, 80.0, 199.0))
def test_drive_derivatives_against_differences(t):
    h = 1e-3
    lo, mid, hi = (drive_state(min(max(x, 0.0), 200.0)) for x in (t - h, t, t + h))
    span = (min(t + h, 200.0) - max(t - h, 0.0))
    assert mid.alpha_rate == pytest.approx((hi.alpha - lo.alpha) / span, rel=1e-6)
    assert mid.gamma_rate == pytest.approx((hi.gamma - lo.gamma) / span, rel=1e-6)
    assert mid.alpha_acc == pytest.approx((hi.alpha_rate - lo.alpha_rate) / span, rel=1e-5)
    assert mid.gamma_acc == pytest.approx((hi.gamma_rate - lo.gamma_rate) / span, rel=1e-5, abs=1e-12)


def test_node_velocities_are_the_derivative_of_eq7():
    h = 1e-4
    s, lo, hi = drive_state(120.0), drive_state(120.0 - h), drive_state(120.0 + h)
    v = GEOMETRY.node_velocities(s.alpha, s.gamma, s.alpha_rate, s.gamma_rate)
    p_lo, p_hi = GEOMETRY.node_positions(lo.alpha, lo.gamma), GEOMETRY.node_positions(hi.alpha, hi.gamma)
    for node, vel in v.items():
        np.testing.assert_allclose(vel, (p_hi[node] - p_lo[node]) / (2 * h), atol=1e-11)


def test_eq10_and_eq13_are_consistent_with_eq12():
    k = GEOMETRY.tangent("B")
    R = rot_axis(k, 0.3)
    assert R @ k == pytest.approx(k)
    np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-15)
    gx, gy, gz = 0.4, -0.7, 2.1
    angles = rpy_angles(rot_z(gz) @ rot_y(gy) @ rot_x(gx))
    np.testing.assert_allclose(angles, [gx, gy, gz], atol=1e-14)


def test_eq9_reading_starts_at_the_printed_initial_orientation():
    R = GEOMETRY.node_rotation("B", GAMMA0)
    np.testing.assert_allclose(R, rot_y(GAMMA0) @ euler_xyz(R_B0_ANGLES), atol=1e-15)


@pytest.mark.parametrize("bad", [{"t": -1.0}, {"t": 201.0}, {"t": float("nan")}])
def test_drive_laws_refuse_times_outside_the_fold(bad):
    with pytest.raises(InvalidParameters, match="t"):
        drive_state(**bad)


@pytest.mark.parametrize("bad", [{"l2": 0.6}, {"alpha_ref": 2.0}, {"L": 2.0}])
def test_params_refuse_impossible_geometry(bad):
    with pytest.raises(InvalidParameters):
        TetraParams(**bad)


@pytest.fixture(scope="module")
def unit(load_cached):
    return load_cached("tetra_3rr3uru")


@pytest.fixture(scope="module")
def unit_fold(unit):
    return fold(unit, np.array(TIMES))


def test_unit_mobility_is_3_without_redundancy(unit, unit_fold):
    for sample in unit_fold:
        mob = unit.mobility(sample.q)
        assert (mob.dof, mob.redundant, mob.rows) == (3, 0, 15)
        assert mob.singular_values[-1] > 1e-6 * mob.singular_values[0]  # weak (see docs) but regular


def test_equal_links_make_the_unit_degenerate(load_cached):
    """With l1 = l2 (equilateral base) the three URU forces along the middle hinges become
    coplanar and concurrent: DOF 4 with one redundant row. The paper's l1 = 0.2504 m, l2 = 0.250 m
    restores DOF 3, hence the small last singular value of the default unit."""
    mob = load_cached("tetra_3rr3uru", l1=0.25).mobility()
    assert (mob.dof, mob.redundant) == (4, 1)


def test_paper_attitude_drives_at_b_and_e_do_not_determine_the_unit(unit):
    assert unit.singularity(unit.home_q, ("AH_H", "BH_B", "EH_E")) > 1e10
    assert unit.singularity(unit.home_q) < 1e7


def test_unit_fold_matches_eq6_eq7_and_closes(unit, unit_fold):
    p = unit.params
    for sample in unit_fold:
        s = drive_state(sample.t)
        expected = p.geometry().node_positions(s.alpha, s.gamma)
        for node, pos in node_positions(unit, sample.q).items():
            np.testing.assert_allclose(pos, expected[node], atol=1e-9)
        assert np.abs(unit.closure_residual(sample.q)).max() < 1e-10
        angles, rates, accs = web_joint_motion(p, s)
        for joint in angles:
            k = unit.v_index(joint)
            assert sample.q[unit.q_index(joint)] == pytest.approx(angles[joint], abs=1e-9)
            assert sample.v[k] == pytest.approx(rates[joint], abs=1e-11)
            assert sample.a[k] == pytest.approx(accs[joint], abs=1e-12)


def test_fold_continuation_takes_the_whole_fold_in_one_requested_step(unit):
    (end,) = fold(unit, np.array([200.0]))
    s = drive_state(200.0)
    expected = unit.params.geometry().node_positions(s.alpha, s.gamma)
    for node, pos in node_positions(unit, end.q).items():
        np.testing.assert_allclose(pos, expected[node], atol=1e-9)


@pytest.mark.parametrize("i", range(len(TIMES)))
def test_soc_agrees_with_constrained_rnea(unit, unit_fold, i):
    sample = unit_fold[i]
    reference = unit.inverse_dynamics(sample.q, sample.v, sample.a)
    result = soc.solve(unit, sample.t)
    assert all(r.determinate.all() for r in reference.reactions.values())  # no redundant row in the unit
    effort_scale = max(abs(u) for u in reference.efforts.values())
    for joint, u in reference.efforts.items():
        assert result.efforts[joint] == pytest.approx(u, abs=1e-8 * effort_scale)
    scale = max(np.abs(r.wrench).max() for r in reference.reactions.values())
    for joint, r in reference.reactions.items():
        np.testing.assert_allclose(result.reactions[joint], r.wrench, atol=1e-8 * scale, err_msg=joint)


def test_soc_independent_motion_matches_pinocchio_forward_kinematics(unit, unit_fold):
    import pinocchio as pin

    motion = soc.UnitMotion(unit.params)
    for sample in unit_fold:
        R, origin = motion.poses(sample.t)
        pin.forwardKinematics(unit.model, unit.data, sample.q)
        for joint in motion.joints:
            placement = unit.data.oMi[unit.model.getJointId(joint.name)]
            np.testing.assert_allclose(placement.rotation, R[joint.child], atol=1e-9)
            np.testing.assert_allclose(placement.translation, origin[joint.child], atol=1e-9)


def test_bench_measures_the_unit_along_its_fold(load_cached):
    """`mechkit bench tetra_3rr3uru` (the measurements of the former tools/deployable_bench.py): states
    along the paper's fold, 18 coordinates and 15 rows; the fold step, SOC and the core's methods all
    timed; the dense KKT keeps J a + gamma = 0 and its accelerations within 10 % of the fold's (which are
    tiny: the fold is quasi-static)."""
    from mechkit.bench.run import bench_mechanism

    mech = load_cached("tetra_3rr3uru")
    b = bench_mechanism(mech, quick=True, with_peers=False)
    assert b.nv == 18 and b.rows_closure == 15
    by = {r.method.name: r for r in b.rows}
    for name in ("closure Newton tol=1e-12", "constraintDynamics mu=1e-09 it=20", "constrained RNEA, no determinacy",
                 *(m.label for m in mech.spec.bench_methods)):
        assert by[name].outcome == "ok" and by[name].median_s > 0, name
    assert all("t" in s.extra for s in b.samples)
    assert by["dense KKT (independent rows)"].error < 0.1
    for s in b.samples:
        a = mech.forward_dynamics(s.q, s.v, s.tau, method="kkt").a
        assert np.abs(mech.closure_jacobian(s.q) @ a + mech.closure_drift(s.q, s.v)).max() < 1e-9
