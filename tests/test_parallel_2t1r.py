"""The 2T1R through the Pinocchio pipeline against the paper's kinematics, SOC and classic virtual work."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest

from mechkit.base.exceptions import ClosureNotConverged, InvalidParameters, SingularConfiguration
from mechkit.base.resources import urdf_dir
from mechkit.mechanisms.parallel_2t1r import SPEC
from mechkit.mechanisms.parallel_2t1r import kinematics as kin
from mechkit.mechanisms.parallel_2t1r.assembly import EXAMPLE_INPUTS
from mechkit.mechanisms.parallel_2t1r.compare import compare_along
from mechkit.mechanisms.parallel_2t1r.joint_state import joint_coordinates
from mechkit.mechanisms.parallel_2t1r.motion_law import motion_law, state_at
from mechkit.mechanisms.parallel_2t1r.params import Parallel2T1RParams, mass_properties
from mechkit.mechanisms.parallel_2t1r.rates import at_rest
from mechkit.mechanisms.parallel_2t1r.soc import classic_torques, skcs, soc_inverse_dynamics
from mechkit.mechanisms.parallel_2t1r.studies import singular_approach, start_of_motion
from mechkit.scenes import scene_poses
from mechkit.sources.xacro_file import render_urdf

REGULAR = np.arange(1, 501) * 0.01  # the 501-sample law without its singular start t = 0


@pytest.fixture(scope="module")
def mech(load_cached):
    return load_cached("parallel_2t1r")


@pytest.fixture(scope="module")
def comparison(mech):
    return compare_along(mech, REGULAR)


def test_urdf_file_is_the_template_at_defaults():
    spec, p = SPEC, Parallel2T1RParams()
    assert (urdf_dir() / "parallel_2t1r.urdf").read_text() == render_urdf(spec.template_path, p.xacro_args())


def test_urdf_inertias_are_the_validators_inertias():
    p = Parallel2T1RParams(payload_mass=3.0, bar_width=0.03)
    root = ET.fromstring(render_urdf(SPEC.template_path, p.xacro_args()))
    for name, (mass, com, inertia) in mass_properties(p).items():
        inertial = root.find(f"link[@name='{name}']/inertial")
        assert float(inertial.find("mass").get("value")) == pytest.approx(mass, rel=1e-14)
        np.testing.assert_allclose([float(x) for x in inertial.find("origin").get("xyz").split()], com, atol=1e-15)
        tensor = inertial.find("inertia")
        np.testing.assert_allclose([float(tensor.get(k)) for k in ("ixx", "iyy", "izz")], np.diag(inertia), rtol=1e-14)


def test_mobility_and_redundant_variant(load_cached):
    plain, redundant = load_cached("parallel_2t1r"), load_cached("parallel_2t1r", redundant_actuation=True)
    assert plain.mobility().dof == 3 and plain.mobility().redundant == 0
    assert plain.actuated == ("R11", "R21", "R31") and redundant.actuated == ("R11", "R21", "R31", "R41")
    np.testing.assert_allclose(redundant.home_q, plain.home_q, atol=1e-12)


def _analytic_q(mech, pose: kin.Pose, theta4: float) -> np.ndarray:
    s = at_rest(pose, EXAMPLE_INPUTS, theta4)
    q = mech.neutral()
    for joint, (value, _, _) in joint_coordinates(mech.params, s).items():
        q[mech.q_index(joint)] = value
    return q


def test_example_assembles_into_every_forward_solution(mech):
    """Each FK pose with each theta_4 root: Pinocchio's closure solve from a guess 0.05 rad away
    lands on the analytic configuration. The one pose limb III cannot reach does not assemble."""
    rng = np.random.default_rng(3)
    assembled = 0
    for sol in kin.forward_kinematics(mech.params.dims, EXAMPLE_INPUTS):
        try:
            roots, _ = kin.follower_angles(mech.params.dims, sol.pose)
        except InvalidParameters:
            with pytest.raises(ClosureNotConverged):
                q0 = _analytic_q(mech, sol.pose, 0.0)
                mech.assemble(EXAMPLE_INPUTS, guess=q0 + rng.uniform(-0.05, 0.05, q0.size), max_iter=40)
            continue
        for theta4 in roots:
            exact = _analytic_q(mech, sol.pose, theta4)
            q = mech.assemble(EXAMPLE_INPUTS, guess=exact + rng.uniform(-0.05, 0.05, exact.size))
            assert np.max(np.abs(mech.closure_residual(q))) < 1e-12
            np.testing.assert_allclose(np.angle(np.exp(1j * (q - exact))), 0.0, atol=1e-10)
            assembled += 1
    assert assembled == 6


def test_soc_and_classic_agree_with_pinocchio_along_the_motion_law(comparison):
    """The 500 regular samples: torques and determinate reactions within 1e-8 of the largest value."""
    assert comparison.kinematics_error.max() < 1e-10
    assert np.all(comparison.relative_error("soc") < 1e-8)
    assert np.all(comparison.relative_error("classic")[:3] < 1e-8)
    assert np.all(np.abs(comparison.values["pinocchio"]).max(axis=0)[[0, 1, 3, 4, 5, 6]] > 0.5)  # not trivial


def test_in_plane_forces_are_the_determinate_components(comparison):
    """All axes parallel: fx, fz (and my of a free pin) are fixed by statics; fy, mx, mz are not."""
    for joint in ("R23", "R43"):
        np.testing.assert_array_equal(comparison.determinate[joint], [True, False, True, False, True, False])


def test_soc_equals_classic_virtual_work_at_one_instant():
    """Two virtual-work routes on the same loads: SKC by SKC, and the whole mechanism at once."""
    p = Parallel2T1RParams()
    s = state_at(p, *motion_law(2.2))
    soc = soc_inverse_dynamics(p, s)
    ours, _ = classic_torques(p, s)
    assert soc.consistency["SKC1"] < 1e-12
    for joint in ("R11", "R21", "R31"):
        assert soc.efforts[joint] == pytest.approx(ours[joint], rel=1e-10)


def test_redundant_minimum_norm_distribution_agrees_everywhere(mech):
    cmp = compare_along(mech, REGULAR[::25], redundant=True)
    assert np.all(cmp.relative_error("soc") < 1e-8)
    assert np.all(cmp.relative_error("classic")[:3] < 1e-8)


def test_start_of_motion_law(mech):
    """t -> 0+: torques tend to finite limits, cond(J_p) and the five-bar's R13 force grow as 1/t;
    at t = 0 every method raises SingularConfiguration (none returns NaN)."""
    times = np.array([1e-1, 1e-2, 1e-3, 1e-4, 0.0])
    study = start_of_motion(mech, times)
    v = study.values
    for key in ("cond_Jp", "pinocchio:R13_fx"):
        slope = np.polyfit(np.log(times[:4]), np.log(np.abs(v[key][:4])), 1)[0]
        assert slope == pytest.approx(-1.0, abs=0.01)
    for method in ("classic", "soc", "pinocchio"):
        m1 = v[f"{method}:M1"][:4]
        assert np.ptp(m1) < 1e-3 * np.abs(m1).max()
    assert {m for m, fails in study.failures.items() if [x for x, _ in fails] == [0.0]} == {
        "analytic", "classic", "soc", "pinocchio"}


def test_singular_approach_blows_up_only_without_redundant_actuation(mech):
    deltas = np.array([1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 0.0])
    study = singular_approach(mech, deltas)
    v, x = study.values, deltas[:-1]
    for key in ("cond_Jp", "classic:cond", "soc:M1", "pinocchio:M1", "pinocchio:M2", "pinocchio:R13_fx"):
        slope = np.polyfit(np.log(x[2:]), np.log(np.abs(v[key][2:-1])), 1)[0]
        assert slope == pytest.approx(-0.5, abs=0.02), key
        assert np.abs(v[key][3:-1]).max() / np.abs(v[key][:3]).max() > 20.0, key
    for key in ("redundant/classic:M1", "redundant/classic:M2", "redundant/classic:M3", "redundant/classic:M4",
                "redundant/classic:cond", "redundant/pinocchio:R13_fx", "redundant/soc:R23_fx"):
        growth = np.abs(v[key][3:-1]).max() / np.abs(v[key][:3]).max()  # 31.6 for delta^-1/2
        assert growth < 1.5, key
    for q in ("M1", "M2", "M3", "M4"):  # converging like delta^1/2 to the value at the singular pose
        gap = np.abs(v[f"redundant/classic:{q}"][3:-1] - v[f"redundant/classic:{q}"][-1])
        assert gap[2] < 0.2 * gap[0], q
    for method in ("classic", "soc", "pinocchio"):  # the plain variant: a clear error at delta = 0
        assert [x for x, _ in study.failures[method]] == [0.0]
    for q in ("M1", "M2", "M3"):  # SOC and Pinocchio, handed M4, reproduce the minimum-norm torques
        ref = v[f"redundant/classic:{q}"][:-1]
        for method in ("soc", "pinocchio"):
            np.testing.assert_allclose(v[f"redundant/{method}:{q}"][:-1], ref, rtol=0, atol=1e-7 * np.abs(ref).max())
    for q in ("R23_fx", "R23_fz", "R43_fx", "R43_fz"):
        ref = v[f"redundant/pinocchio:{q}"][:-1]
        np.testing.assert_allclose(v[f"redundant/soc:{q}"][:-1], ref, rtol=0, atol=1e-7 * np.abs(ref).max())


def test_self_checks_report(mech):
    checks = SPEC.self_checks(mech)
    assert checks and all(np.isfinite(x) and x < 1e-8 for x in checks.values())


def test_skc_order_and_unknowns():
    p = Parallel2T1RParams()
    s = state_at(p, *motion_law(1.0))
    names = [(k.name, [a for a, _ in k.actuators], [r.joint for r in k.released], [r.joint for r in k.known])
             for k in skcs(p, s)]
    assert names == [("SKC3", [], ["R43"], []), ("SKC2", ["R31"], ["R23"], ["R43"]),
                     ("SKC1", ["R11", "R21"], [], ["R23"])]
    with pytest.raises(SingularConfiguration):
        classic_torques(p, s, ("R11", "R21"))  # two motors cannot hold three DOF


def test_motion_law_scene_closes_every_loop(mech):
    poses = scene_poses(mech, "motion_law")  # checks sizes, finiteness and closure
    assert len(poses) == 101
    np.testing.assert_allclose([q[mech.q_index("R21")] for q in poses], np.pi / 15 * np.linspace(0, 5, 101), atol=1e-15)


def test_studies_write_both_figures(mech, tmp_path):
    """The comparison (10 samples) and the singular studies drawn (moved from test_parallel_2t1r_tools.py)."""
    from mechkit.mechanisms.parallel_2t1r.figures import comparison_figure, singular_figure
    from mechkit.mechanisms.parallel_2t1r.studies import comparison, singular

    comparison_figure(comparison(mech, 10), tmp_path)
    singular_figure(singular(mech), tmp_path)
    for name in ("comparison", "singular"):
        png = tmp_path / f"parallel_2t1r_{name}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000


def test_bench_runs_every_method(mech):
    """`mechkit bench parallel_2t1r` (the rows of the former tools/parallel_2t1r_bench.py): Pinocchio's
    constrained RNEA with and without the determinacy test, SOC, classic virtual work and the paper's
    position analysis, each timed, SOC and classic agreeing with the reference."""
    from mechkit.bench.run import bench_mechanism

    b = bench_mechanism(mech, quick=True, with_peers=False)
    by = {r.method.name: r for r in b.rows}
    for name in ("constrained RNEA + determinacy", "constrained RNEA, no determinacy",
                 "SOC, 3 SKCs (numpy, from the analytic state)", "classic virtual work (numpy, from the analytic state)",
                 "paper FK (eqs. 7-9) + closed-form joints"):
        assert by[name].outcome == "ok" and by[name].median_s > 0 and by[name].error < 1e-9, name
    assert by["classic virtual work (numpy, from the analytic state)"].note == "efforts only"


def test_declared_motion_law_is_the_papers(mech):
    """`SPEC.motion_laws["motion_law"]` samples the paper's law exactly (values, rates, accelerations),
    without its singular start, as `motion.from_callable` does."""
    from mechkit import motion
    from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_DURATION

    law = motion.from_law(mech, "motion_law", 7)
    ref = motion.from_callable(mech, motion_law, np.linspace(MOTION_DURATION / 7, MOTION_DURATION, 7))
    assert law.names == ("R11", "R21", "R31") == ref.names
    for field in ("t", "values", "rates", "accelerations"):
        assert np.array_equal(getattr(law, field), getattr(ref, field)), field
    assert len(motion.from_law(mech, "motion_law").t) == 501
    with pytest.raises(InvalidParameters, match="declares the motion laws: motion_law"):
        motion.from_law(mech, "nothing")
