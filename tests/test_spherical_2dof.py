"""2-DOF spherical platform: the paper's kinematics, the Pinocchio model and SOC dynamics agree."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechkit.base.exceptions import ClosureNotConverged, InvalidParameters
from mechkit.loading import load
from mechkit.mechanisms.spherical_2dof import SPEC, Spherical2DofParams, checks, soc
from mechkit.mechanisms.spherical_2dof import kinematics as kin
from mechkit.mechanisms.spherical_2dof.fk import NEAR_SINGULAR, REGULAR, basin_study
from mechkit.mechanisms.spherical_2dof.joint_state import state
from mechkit.mechanisms.spherical_2dof.kinematics import BRANCHES, platform_normal
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude, cone_times

P = Spherical2DofParams()


@pytest.fixture(scope="module")
def mech():
    return load("spherical_2dof")


def test_defaults_are_the_papers_values():
    deg = {
        k: math.degrees(getattr(P, k))
        for k in ("alpha1", "alpha2", "beta", "eta11", "eta12", "eta21", "eta22")
    }
    assert deg == pytest.approx(
        {"alpha1": 25, "alpha2": 30, "beta": 53.13, "eta11": 0, "eta12": 90, "eta21": 0, "eta22": 90},
        abs=1e-12,
    )


@pytest.mark.parametrize(
    "change, name",
    [
        ({"beta_platform": P.beta}, "beta_platform"),
        ({"beta_platform": math.radians(150)}, "beta_platform"),
        ({"alpha1": 0.0}, "alpha1"),
        ({"rows": "planar"}, "rows"),
    ],
)
def test_bad_parameters_are_named(change, name):
    with pytest.raises(InvalidParameters) as err:
        P.replace(**change)
    assert err.value.name == name


def test_middle_axis_is_eq4_as_printed():
    """w_i of our chain equals the third column (a13, a23, a33) printed in eq. (4)."""
    s, c = np.sin, np.cos
    a1, b = P.alpha1, P.beta
    for i, eta in ((1, P.eta11), (2, P.eta12)):
        for th in np.linspace(-3, 3, 7):
            printed = [
                -s(a1) * c(eta) * s(th) + s(a1) * s(eta) * c(b) * c(th) + s(eta) * s(b) * c(a1),
                -s(a1) * s(eta) * s(th) - s(a1) * c(eta) * c(b) * c(th) - c(a1) * c(eta) * s(b),
                s(b) * c(th) * s(a1) - c(b) * c(a1),
            ]
            np.testing.assert_allclose(kin.middle_axis(P, i, th), printed, atol=1e-15)


def test_ik_both_branches_close_eq7_and_differ():
    for phi in cone_attitude(cone_times(9))[0]:
        plus, minus = (kin.inverse_kinematics(P, phi, (k, k)) for k in (1, -1))
        assert np.abs(kin.constraint(P, plus, phi)).max() < 1e-14
        assert np.abs(kin.constraint(P, minus, phi)).max() < 1e-14
        assert np.abs(plus - minus).min() > 0.5


def test_unreachable_attitude_raises():
    with pytest.raises(InvalidParameters) as err:
        kin.inverse_kinematics(P, np.radians([-40.0, 0.0]))
    assert err.value.name == "phi"


def test_cone_scene_derivatives_and_angle():
    t, h = np.linspace(0, 2, 11), 1e-5
    phi, phi_d, phi_dd = cone_attitude(t)
    np.testing.assert_allclose(np.degrees(np.arccos(platform_normal(phi)[:, 2])), 15.0, atol=1e-12)
    fd = (cone_attitude(t + h)[0] - cone_attitude(t - h)[0]) / (2 * h)
    np.testing.assert_allclose(phi_d, fd, atol=1e-8)
    fd2 = (cone_attitude(t + h)[1] - cone_attitude(t - h)[1]) / (2 * h)
    np.testing.assert_allclose(phi_dd, fd2, atol=1e-7)


def test_cone_round_trip_ik_then_paper_fk():
    """IK gives the motor curves; the paper's FK of those curves returns the planned path."""
    attitude, marker = checks.cone_round_trip(P, 72)
    assert attitude < 1e-10 and marker < 1e-10


def test_jacobian_against_finite_differences():
    assert checks.jacobian_fd_error(P, 12) < 1e-7


def test_jacobian_against_pinocchio_velocity_projection(mech):
    """Hooke rates from the core's closure Jacobian equal J theta' (J = -B^-1 A)."""
    for phi in cone_attitude(cone_times(6))[0]:
        theta = kin.inverse_kinematics(P, phi, BRANCHES)
        q, _, _ = state(mech, phi, np.zeros(2), np.zeros(2))
        for rates in np.eye(2):
            v = mech.velocities(q, rates)
            hooke = v[[mech.v_index("hooke_roll"), mech.v_index("hooke_pitch")]]
            np.testing.assert_allclose(hooke, kin.jacobian(P, theta, phi) @ rates, atol=1e-12)


def test_printed_fk_step_does_not_converge():
    """The step as printed, -J^-1 (theta_d - theta_k), wanders off; J (theta_d - theta_k) converges."""
    target = cone_attitude(0.3)[0]
    theta_d = kin.inverse_kinematics(P, target, BRANCHES)
    phi = target + 0.02
    for _ in range(30):
        try:
            theta = kin.inverse_kinematics(P, phi, BRANCHES)
        except InvalidParameters:
            break
        phi = phi - np.linalg.solve(kin.jacobian(P, theta, phi), theta_d - theta)
    assert np.abs(phi - target).max() > 1e-3
    assert np.abs(kin.fk_paper(P, theta_d, target + 0.02).phi - target).max() < 1e-12


def test_home_assembles_with_two_dof(mech):
    assert np.abs(mech.closure_residual(mech.home_q)).max() < 1e-12
    mob = mech.mobility()
    assert mob.dof == 2 == SPEC.gruebler_dof and mob.redundant == 0


def test_spatial_rows_are_six_redundant_constraints():
    """With 5 spatial rows per cut the mobility stays 2 and 6 rows are redundant: the spatial
    Kutzbach-Gruebler count 6 (6 - 7 - 1) + 8 = -4 = 2 - 6 (the common constraints of a spherical linkage)."""
    mob = load("spherical_2dof", rows="spatial").mobility()
    assert (mob.dof, mob.redundant, mob.rows) == (2, 6, 10)


def test_analytic_state_satisfies_pinocchio_closure(mech):
    t = cone_times(8)
    for phi, phi_d, phi_dd in zip(*cone_attitude(t)):
        q, v, a = state(mech, phi, phi_d, phi_dd)
        assert np.abs(mech.closure_residual(q)).max() < 1e-13
        assert np.abs(mech.closure_jacobian(q) @ v).max() < 1e-12
        assert np.abs(mech.closure_jacobian(q) @ a + mech.closure_drift(q, v)).max() < 1e-11


def test_fk_methods_agree(mech):
    assert checks.fk_agreement(mech, 12) < 1e-10


def test_mechanism_assemble_is_the_forward_kinematics(mech):
    """`Mechanism.assemble` from the motor angles (home guess) returns the planned attitude."""
    for phi in cone_attitude(cone_times(6))[0]:
        theta = kin.inverse_kinematics(P, phi, BRANCHES)
        q = mech.assemble(theta, guess=mech.home_q, tol=1e-13)
        found = q[[mech.q_index("hooke_roll"), mech.q_index("hooke_pitch")]]
        assert np.abs(found - phi).max() < 1e-10


def test_closure_fk_from_a_hopeless_start_raises(mech):
    theta_d = kin.inverse_kinematics(P, np.zeros(2))
    with pytest.raises(ClosureNotConverged):
        kin.fk_newton(P, theta_d, np.radians([170.0, 80.0]), max_iter=5)


def test_basin_study():
    """Regular pose: every method finds the answer from 1 and 5 deg away; at 20 deg the paper's
    method loses starts (its iterates leave the workspace, where InvKin is undefined) that Newton
    keeps. 0.4 deg from the forward singularity the other assembly mode (the mirror root across
    det B = 0) captures starts 1 deg away, from every method."""
    mech = load("spherical_2dof")
    regular = basin_study(mech, REGULAR, np.radians([1.0, 5.0, 20.0]), 12)
    table = {(r.method, round(math.degrees(r.radius))): r for r in regular}
    for method in ("paper", "newton", "closure"):
        assert table[method, 1].found == table[method, 5].found == 1.0
    assert table["paper", 20].failed > 0.0 and table["newton", 20].found > table["paper", 20].found
    near = basin_study(mech, NEAR_SINGULAR, np.radians([0.1, 1.0]), 12)
    for r in near:
        assert (r.found == 1.0) if r.radius < 0.01 else (r.elsewhere > 0.0)


def test_soc_inertias_match_the_urdf(mech):
    """The SOC's body inertias (re-derived from the sizes) equal Pinocchio's parse of the xacro."""
    for name, (m, com, inertia) in soc.body_inertias(P).items():
        frame = mech.model.getFrameId(name)
        body = mech.model.inertias[mech.model.frames[frame].parentJoint]
        assert body.mass == pytest.approx(m, rel=1e-12)
        np.testing.assert_allclose(body.lever, com, atol=1e-15)
        np.testing.assert_allclose(body.inertia, inertia, atol=1e-15)


def test_dynamics_pinocchio_vs_soc(mech):
    """Motor torques, the support moment and every joint's moment about O (the determinate parts)."""
    errors = checks.dynamics_agreement(mech, 24)
    assert errors["efforts"] < 1e-8 and errors["support"] < 1e-8 and errors["joints"] < 1e-8
    assert errors["consistency"] < 1e-10


def test_motor_power_equals_rate_of_energy(mech):
    """sum tau_i theta_i1' = dE/dt (kinetic + gravity), E from the body motions, by central differences."""
    g, h = 9.81, 1e-4

    def energy(t: float) -> float:
        total = 0.0
        for b in soc.body_motions(P, *(x for x in cone_attitude(t))).values():
            v = kin.cross(b.omega, b.com)
            total += 0.5 * b.mass * v @ v + 0.5 * b.omega @ b.inertia @ b.omega + b.mass * g * b.com[2]
        return total

    for t in cone_times(6):
        phi, phi_d, phi_dd = cone_attitude(t)
        q, v, a = state(mech, phi, phi_d, phi_dd)
        rates = v[[mech.v_index(j) for j in mech.actuated]]
        reference = (energy(t + h) - energy(t - h)) / (2 * h)
        pin_power = rates @ [mech.inverse_dynamics(q, v, a).efforts[j] for j in mech.actuated]
        soc_power = rates @ [soc.solve(P, phi, phi_d, phi_dd).efforts[j] for j in mech.actuated]
        assert pin_power == pytest.approx(reference, abs=1e-8)
        assert soc_power == pytest.approx(reference, abs=1e-8)


def test_support_determinacy(mech):
    """Every body turns about O: forces at O are indeterminate, moments (about O) determinate."""
    phi, phi_d, phi_dd = (x[0] for x in cone_attitude(np.array([0.4])))
    q, v, a = state(mech, phi, phi_d, phi_dd)
    result = mech.inverse_dynamics(q, v, a)
    for name, reaction in result.reactions.items():
        assert not reaction.determinate[:3].any(), name
        assert reaction.determinate[3:].all(), name
    assert abs(result.reactions["hooke_roll"].wrench[3]) < 1e-12  # the roll axis X0 is free


def test_studies_draw_their_figures(mech, tmp_path):
    """The cone scene and the basins on tiny runs, drawn (moved from test_tools_run, which ran the tools)."""
    from mechkit.mechanisms.spherical_2dof.figures import basin_figure, cone_figure
    from mechkit.mechanisms.spherical_2dof.studies import basin, cone, cone_summary

    c = cone(mech, samples=6)
    summary = cone_summary(c)
    assert summary["torques Pinocchio vs SOC (N m)"] < 1e-12 and summary["FK vs plan, attitude (rad)"] < 1e-12
    for path in (*cone_figure(c, tmp_path), *basin_figure(basin(mech, directions=2, grid_points=11), tmp_path)):
        assert path.stat().st_size > 10_000


def test_bench_runs_every_method(mech):
    """`mechkit bench spherical_2dof` (the rows of the former tools/spherical_2dof_bench.py): IK eq. (8),
    the paper's FK, Newton FK, the core's closure solver, Pinocchio's inverse dynamics with and without
    the determinacy test and SOC, each timed."""
    from mechkit.bench.run import bench_mechanism

    b = bench_mechanism(mech, quick=True, with_peers=False)
    by = {r.method.name: r for r in b.rows}
    for name in ("closure Newton tol=1e-12", "constrained RNEA + determinacy", "constrained RNEA, no determinacy",
                 *(m.label for m in SPEC.bench_methods)):
        assert by[name].outcome == "ok" and by[name].median_s > 0, name
    assert by["IK eq. (8)"].method.quantity == "inverse_kinematics" and by["IK eq. (8)"].error < 1e-10


def test_cut_joint_angle_matches_pinocchio_frames(mech):
    """The cut frames of r{i}3 differ by Rz(theta_i3) of `kin.limb_angles` (xacro = our chain)."""
    import pinocchio as pin

    for phi in cone_attitude(cone_times(4))[0]:
        theta = kin.inverse_kinematics(P, phi, BRANCHES)
        q, _, _ = state(mech, phi, np.zeros(2), np.zeros(2))
        pin.framesForwardKinematics(mech.model, mech.data, q)
        for k, i in enumerate((1, 2)):
            rot = [
                mech.data.oMf[mech.model.getFrameId(f)].rotation for f in (f"link{i}2_C", f"platform_C{i}")
            ]
            np.testing.assert_allclose(
                rot[0].T @ rot[1], kin.rot_z(kin.limb_angles(P, i, theta[k], phi)[1]), atol=1e-14
            )


def test_other_branch_closes_and_dynamics_agree(mech):
    """The other IK branch (-1, -1) is an assembly too; Pinocchio and SOC agree on it."""
    branches = (-1, -1)
    for phi, phi_d, phi_dd in zip(*cone_attitude(cone_times(4)), strict=True):
        q, v, a = state(mech, phi, phi_d, phi_dd, branches)
        assert np.abs(mech.closure_residual(q)).max() < 1e-13
        assert np.abs(mech.closure_jacobian(q) @ a + mech.closure_drift(q, v)).max() < 1e-11
        ref = mech.inverse_dynamics(q, v, a).efforts
        ours = soc.solve(P, phi, phi_d, phi_dd, branches).efforts
        for joint in mech.actuated:
            assert ours[joint] == pytest.approx(ref[joint], rel=1e-9, abs=1e-12)
