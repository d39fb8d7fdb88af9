"""The engine gimbal as a mechkit Mechanism: FK three ways, analytic motion vs Pinocchio, dynamics vs SOC."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.rocket_gimbal.checks import dynamics_agreement, fk_agreement, fk_closure
from mechkit.mechanisms.rocket_gimbal.joint_state import joint_state
from mechkit.mechanisms.rocket_gimbal.kinematics import strokes
from mechkit.mechanisms.rocket_gimbal.params import body_inertias, geometry
from mechkit.mechanisms.rocket_gimbal.resultant import fk_resultant
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene, thrust_fext
from mechkit.mechanisms.rocket_gimbal.soc import soc_skcs
from mechkit.validation.soc import solve_soc


@pytest.fixture(scope="module")
def mech(load_cached):
    return load_cached("rocket_gimbal")


def test_fk_polynomial_newton_and_closure_solver_agree_over_the_stroke_square(mech):
    # 7 x 7 strokes over +-110 mm, diagonal (double root of the resultant) included
    fk = fk_agreement(mech, n=7)
    assert fk.polynomial_newton < 1e-9 and fk.polynomial_closure < 1e-9 and fk.newton_closure < 1e-9
    assert fk.ik_round_trip < 1e-9
    assert fk.worst_condition < 1e3


def test_closure_solver_reaches_the_flipped_mode_from_its_guess(mech):
    geo = geometry(mech.params)
    stroke = np.array([-0.06, 0.105])
    flipped = [m for m in fk_resultant(geo, stroke) if m.nozzle_z < 0]
    target = min(flipped, key=lambda m: abs(m.alpha) + abs(m.beta))
    guess = {"bracket_hinge": target.alpha + 0.02, "engine_hinge": target.beta - 0.02}
    angles, _ = fk_closure(mech, stroke, guess=guess)
    assert np.allclose(angles, [target.alpha, target.beta], atol=1e-9)
    assert np.allclose(strokes(geo, *angles), stroke, atol=1e-9)


def test_urdf_inertias_are_the_python_body_inertias(mech):
    model = mech.model
    for body, (mass, transverse, axial) in body_inertias(mech.params).items():
        frame = model.frames[model.getFrameId(body)]
        inertia = model.inertias[frame.parentJoint]
        assert np.isclose(inertia.mass, mass, rtol=1e-12)
        assert np.allclose(
            np.sort(np.linalg.eigvalsh(inertia.inertia)), np.sort([transverse, transverse, axial]), rtol=1e-12
        )


@pytest.mark.parametrize("t", [0.05, 0.3, 0.77])
def test_analytic_motion_satisfies_pinocchios_closure_rows(mech, t):
    scene = SwingScene()
    q, v, a = joint_state(mech, scene.motion(mech.params, t))
    J = mech.closure_jacobian(q)
    assert np.abs(mech.closure_residual(q)).max() < 1e-12
    assert np.abs(J @ v).max() < 1e-12
    assert np.abs(J @ a + mech.closure_drift(q, v)).max() < 1e-11
    # Pinocchio's velocity / acceleration projection from the stroke rates gives the same motion
    rates = {j: v[mech.v_index(j)] for j in mech.actuated}
    accs = {j: a[mech.v_index(j)] for j in mech.actuated}
    assert np.allclose(mech.velocities(q, rates), v, atol=1e-12)
    assert np.allclose(mech.accelerations(q, v, accs), a, atol=1e-10)


def test_inverse_dynamics_pinocchio_vs_soc_over_a_swing(mech):
    agreement = dynamics_agreement(mech)
    assert agreement.missing == ()  # every joint's reaction is compared
    assert agreement.indeterminate == 0  # spherical cuts with 3 rows: everything determinate
    assert agreement.efforts < 1e-8 and agreement.reactions < 1e-8
    assert agreement.consistency < 1e-10


def test_thrust_through_the_swing_centre_loads_the_bearings_not_the_servos(mech):
    scene, idle = SwingScene(), SwingScene(thrust=0.0)
    motion = scene.motion(mech.params, 0.2)
    q, v, a = joint_state(mech, motion)
    loaded = mech.inverse_dynamics(q, v, a, fext=thrust_fext(mech, q, scene))
    free = mech.inverse_dynamics(q, v, a, fext=thrust_fext(mech, q, idle))
    for name in mech.actuated:
        assert np.isclose(loaded.efforts[name], free.efforts[name], rtol=1e-9)
    nozzle = mech.data.oMi[mech.model.getJointId("engine_hinge")].rotation[:, 2]
    thrust = -scene.thrust * nozzle
    for joint in ("bracket_hinge", "engine_hinge"):
        change = loaded.reactions[joint].wrench - free.reactions[joint].wrench
        assert np.allclose(change[:3], -thrust, rtol=0, atol=1e-6 * scene.thrust)
        assert np.allclose(change[3:], 0.0, atol=1e-6 * scene.thrust)


def test_supports_carry_the_whole_weight_at_rest(mech):
    # Global balance: at rest (null pose, no thrust) the three supports hold exactly the weight.
    scene = SwingScene(amplitude_alpha=0.0, amplitude_beta=0.0, thrust=0.0)
    motion = scene.motion(mech.params, 0.0)
    rest = solve_soc(soc_skcs(mech.params, motion, scene))
    q, v, a = joint_state(mech, motion)
    pin_rest = mech.inverse_dynamics(q, v, a)
    weight = 9.81 * sum(m for m, _, _ in body_inertias(mech.params).values())
    supports = ("bracket_hinge", "a_swing_1", "b_swing_1")
    assert np.isclose(sum(rest.reactions[j][2] for j in supports), weight, rtol=1e-12)
    assert np.isclose(sum(pin_rest.reactions[j].wrench[2] for j in supports), weight, rtol=1e-12)


@pytest.mark.slow
def test_fk_three_ways_on_a_dense_grid(mech):
    fk = fk_agreement(mech, n=21)
    assert max(fk.polynomial_newton, fk.polynomial_closure, fk.newton_closure) < 1e-9
    assert fk.ik_round_trip < 1e-9


def test_root_loss_cases_are_finite_or_named(mech):
    """The gimbal's failure-atlas study (moved from test_failure_atlas.py): each root is found with a
    finite error, or its loss is named, never a silent NaN."""
    from conftest import assert_failures_named

    from mechkit.mechanisms.rocket_gimbal.failure import root_loss

    assert_failures_named(root_loss(mech, quick=True))


def test_linearisation_study_finds_the_worst_error_at_a_corner(tmp_path):
    """The linear rule's error map (moved from test_rocket_gimbal_tools.py), on a 5 x 5 grid, and its figure."""
    from mechkit.mechanisms.rocket_gimbal.figures import linearisation_figure
    from mechkit.mechanisms.rocket_gimbal.params import RocketGimbalParams
    from mechkit.mechanisms.rocket_gimbal.studies import linearisation, linearisation_summary

    study = linearisation(geometry(RocketGimbalParams()), n=5)
    result = linearisation_summary(study)
    # on a 5 x 5 grid the corners are included: the worst error sits at a corner
    assert 0.4 < result["worst_deg"] < 0.6 and abs(result["worst_at_mm"][0]) == 110.0
    assert np.isclose(result["worst_percent"], 100 * result["worst_deg"] / 6.5)
    [png] = linearisation_figure(study, tmp_path)
    assert png.stat().st_size > 10_000


def test_conditioning_study_reports_the_example_and_the_double_root(tmp_path):
    """The resultant's conditioning (moved from test_rocket_gimbal_tools.py): the paper's example, the
    in-range pick, and on the diagonal dlA = dlB a double root, badly conditioned."""
    from mechkit.mechanisms.rocket_gimbal.figures import conditioning_figure
    from mechkit.mechanisms.rocket_gimbal.params import RocketGimbalParams
    from mechkit.mechanisms.rocket_gimbal.studies import conditioning, conditioning_lines

    study = conditioning(geometry(RocketGimbalParams()), n=5)
    text = "\n".join(conditioning_lines(study))
    assert "in-range pick" in text and "double root" in text
    assert np.degrees(study.example.pick.alpha) == pytest.approx(6.629362, abs=1e-6)
    off = study.grid.off_diagonal
    assert np.nanmax(study.grid.condition[~off]) > 1e6 * np.nanmax(study.grid.condition[off])
    [png] = conditioning_figure(study, tmp_path)
    assert png.stat().st_size > 10_000


def test_swing_study_compares_pinocchio_and_soc(mech, tmp_path):
    """One period of the swing by both methods (moved from test_rocket_gimbal_tools.py), and its figure."""
    from mechkit.mechanisms.rocket_gimbal.figures import swing_figure
    from mechkit.mechanisms.rocket_gimbal.studies import swing, swing_summary

    study = swing(mech, n=6)
    result = swing_summary(study)
    assert result["worst relative difference Pinocchio vs SOC"] < 1e-8
    assert 1.1 < result["bearing force max (MN)"] < 1.3  # the 1.2 MN thrust plus weight and inertia
    [png] = swing_figure(study, tmp_path)
    assert png.stat().st_size > 10_000


def test_bench_measures_every_own_method(mech):
    """`mechkit bench rocket_gimbal` runs the paper's FK, Newton FK, the closed-form IK and SOC (the
    timings of the former tools/rocket_gimbal_bench.py): each a finite, positive time."""
    from mechkit.bench.run import bench_mechanism

    b = bench_mechanism(mech, quick=True, with_peers=False)
    own = {r.method.name: r for r in b.rows if r.method.name in {m.label for m in mech.spec.bench_methods}}
    assert set(own) == {m.label for m in mech.spec.bench_methods}
    assert {r.method.quantity for r in own.values()} == {"assembly", "inverse_kinematics", "inverse_dynamics"}
    assert all(r.outcome == "ok" and np.isfinite(r.median_s) and r.median_s > 0 for r in own.values())
