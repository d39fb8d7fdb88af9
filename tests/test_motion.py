"""Motion studies: the study against per-sample inverse dynamics and the power balance, input laws, the
table round trips (DataFrame, Parquet, CSV), and peaks against the table's own maxima."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit import motion
from mechkit.base.exceptions import InvalidParameters, MalformedDescription
from mechkit.mechanisms.parallel_2t1r.motion_law import MOTION_DURATION, MOTION_RATES, motion_law
from mechkit.motion.peaks import QUANTITIES
from mechkit.motion.result import AXES, COMPONENTS
from mechkit.scenes import scene_times


def crank_law(t: float):
    """Four-bar crank: a smooth swing (rad, rad/s, rad/s^2)."""
    w = 2.0
    return np.array([0.6 + 0.3 * np.sin(w * t)]), np.array([0.3 * w * np.cos(w * t)]), np.array([-0.3 * w * w * np.sin(w * t)])


@pytest.fixture(scope="module")
def two_t1r(load_cached):
    mech = load_cached("parallel_2t1r")
    law = motion.from_callable(mech, motion_law, np.linspace(0.2, MOTION_DURATION, 12))
    return mech, motion.study(mech, law, determinacy=True)


@pytest.fixture(scope="module")
def four_bar(load_cached):
    mech = load_cached("four_bar")
    return mech, motion.study(mech, motion.from_callable(mech, crank_law, np.linspace(0.0, 3.0, 16)))


def test_study_equals_per_sample_inverse_dynamics(two_t1r):
    mech, r = two_t1r
    for i in range(len(r.t)):
        closure = np.abs(mech.closure_residual(r.q[i])).max()
        assert closure < 1e-10
        ref = mech.inverse_dynamics(r.q[i], r.v[i], r.a[i])
        assert np.allclose(r.efforts[i], [ref.efforts[j] for j in r.effort_names], rtol=1e-12, atol=1e-12)
        for j, joint in enumerate(r.joints):
            assert np.allclose(r.reactions[i, j], ref.reactions[joint].wrench, rtol=1e-12, atol=1e-10)
            assert np.array_equal(r.determinate[i, j], ref.reactions[joint].determinate)


@pytest.mark.parametrize("case", ["two_t1r", "four_bar"])
def test_inputs_and_power_balance(case, request):
    """The drives' power u . input rates equals v . (M a + nle) (J v = 0: the closures do no work),
    and the inputs follow the law."""
    mech, r = request.getfixturevalue(case)
    for i in range(len(r.t)):
        rates = [r.v[i, mech.v_index(j)] for j in r.effort_names]
        power = float(np.dot(r.efforts[i], rates))
        rate_of_energy = float(r.v[i] @ pin.rnea(mech.model, mech.data, r.q[i], r.v[i], r.a[i]))
        assert power == pytest.approx(rate_of_energy, rel=1e-9, abs=1e-9)
    if case == "two_t1r":
        assert np.allclose(r.v[:, [mech.v_index(j) for j in ("R11", "R21", "R31")]], MOTION_RATES, atol=1e-14)


def test_passive_input_effort_closes_the_power_balance(load_cached):
    """Ten-bar: R5 is an input of the law without an actuator; its effort is what its spring does not give:
    efforts and spring together deliver the power the motion takes."""
    mech = load_cached("ten_bar")
    home = [mech.home_q[mech.q_index(j)] for j in ("R1", "R3", "R5")]

    def law(t):
        return np.array(home) + np.array([-0.05, 0.05, 0.02]) * np.sin(t)

    r = motion.study(mech, motion.from_callable(mech, law, np.linspace(0.0, 1.0, 6)))
    assert r.effort_names == ("R1", "R3", "R5") and r.actuated == ("R1", "R3")
    for i in range(len(r.t)):
        power = r.efforts[i] @ r.v[i, [mech.v_index(j) for j in r.effort_names]] + r.v[i] @ mech.passive_forces(r.q[i], r.v[i])
        assert power == pytest.approx(r.v[i] @ pin.rnea(mech.model, mech.data, r.q[i], r.v[i], r.a[i]), rel=1e-9)


def test_callable_differences_and_spline_agree_with_exact_derivatives(load_cached):
    mech = load_cached("four_bar")
    t = np.linspace(0.0, 3.0, 301)
    exact = motion.from_callable(mech, crank_law, t)
    differenced = motion.from_callable(mech, lambda x: crank_law(x)[0], t)
    assert np.allclose(differenced.rates, exact.rates, atol=1e-9)
    assert np.allclose(differenced.accelerations, exact.accelerations, atol=1e-6)
    splined = motion.from_arrays(mech, t, exact.values[:, 0])
    inner = slice(10, -10)  # not-a-knot ends are less accurate
    assert np.allclose(splined.rates[inner], exact.rates[inner], atol=1e-6)
    assert np.allclose(splined.accelerations[inner], exact.accelerations[inner], atol=1e-3)


def test_csv_law(load_cached, tmp_path):
    mech = load_cached("four_bar")
    exact = motion.from_callable(mech, crank_law, np.linspace(0.0, 1.0, 5))
    path = tmp_path / "law.csv"
    rows = ["t,crank,crank_dot,crank_ddot"] + [
        f"{float(t)!r},{float(x[0])!r},{float(v[0])!r},{float(a[0])!r}" for t, x, v, a in zip(exact.t, exact.values, exact.rates, exact.accelerations)]
    path.write_text("# a crank swing\n" + "\n".join(rows) + "\n")
    law = motion.from_csv(mech, path)
    assert law.names == ("crank",)
    for field in ("t", "values", "rates", "accelerations"):
        assert np.array_equal(getattr(law, field), getattr(exact, field))


@pytest.mark.parametrize("text, needle", [("crank\n0.1\n0.2\n", "'t' column"), ("t,crank\n0,0.6\n1,x\n", "not a number"),
                                          ("t,crank\n0,0.6\n0,0.7\n1,0.8\n2,0.9\n", "strictly increasing"),
                                          ("t,wheel\n0,0.6\n1,0.7\n2,0.8\n3,0.9\n", "'wheel'")])
def test_bad_csv_law_is_a_named_error(load_cached, tmp_path, text, needle):
    path = tmp_path / "law.csv"
    path.write_text(text)
    with pytest.raises((InvalidParameters, MalformedDescription), match=needle):
        motion.from_csv(load_cached("four_bar"), path)


def test_scene_time_axis(load_cached):
    mech = load_cached("parallel_2t1r")
    assert np.allclose(scene_times(mech, "motion_law", 101), np.linspace(0.0, MOTION_DURATION, 101))
    law = motion.from_scene(mech, "motion_law")
    assert np.allclose(law.rates, MOTION_RATES, atol=1e-9)  # linear inputs: the spline is exact
    assert np.array_equal(scene_times(load_cached("four_bar"), "sweep", 3), [0.0, 1.0, 2.0])


def _assert_same(a: motion.MotionResult, b: motion.MotionResult) -> None:
    for field in ("t", "q", "v", "a", "efforts", "reactions", "axes", "supports"):
        assert np.array_equal(getattr(a, field), getattr(b, field), equal_nan=True), field
    assert (a.determinate is None) == (b.determinate is None)
    if a.determinate is not None:
        assert np.array_equal(a.determinate, b.determinate)
    for field in ("mechanism", "source", "coordinates", "effort_names", "actuated", "joints", "failures"):
        assert getattr(a, field) == getattr(b, field), field


def test_round_trips(two_t1r, tmp_path):
    _, r = two_t1r
    _assert_same(r, motion.MotionResult.from_dataframe(r.to_dataframe()))
    motion.write_parquet(r, tmp_path / "m.parquet")
    _assert_same(r, motion.read_parquet(tmp_path / "m.parquet"))
    motion.write_csv(r, tmp_path / "m.csv")
    _assert_same(r, motion.read_csv(tmp_path / "m.csv"))


def test_failures_round_trip(load_cached, tmp_path):
    """The 2T1R law's start is singular: skipped as a row of NaN, named, and kept through the files."""
    mech = load_cached("parallel_2t1r")
    r = motion.study(mech, motion.resample(motion.from_scene(mech, "motion_law"), 5), skip_failures=True)
    assert len(r.failures) == 1 and r.failures[0][0] == 0.0 and "singular" in r.failures[0][1]
    assert np.all(np.isnan(r.efforts[0])) and np.all(np.isfinite(r.efforts[1:]))
    motion.write_parquet(r, tmp_path / "m.parquet")
    _assert_same(r, motion.read_parquet(tmp_path / "m.parquet"))


def test_peaks_are_the_table_maxima(two_t1r):
    _, r = two_t1r
    df = r.to_dataframe()
    peaks = motion.peak_table(r)
    for joint in r.joints:
        f = df[[f"reaction/{joint}/{c}" for c in COMPONENTS[:3]]].to_numpy()
        m = df[[f"reaction/{joint}/{c}" for c in COMPONENTS[3:]]].to_numpy()
        n = df[[f"axis/{joint}/{c}" for c in AXES]].to_numpy()
        for name, vec in (("force", f), ("moment", m)):
            axial = np.abs(np.sum(vec * n, axis=1))
            radial = np.sqrt(np.maximum(np.sum(vec**2, axis=1) - axial**2, 0.0))
            for kind, values in ((name, np.linalg.norm(vec, axis=1)), (f"axial_{name}", axial), (f"radial_{name}", radial)):
                assert peaks.loc[joint, kind] == pytest.approx(values.max(), rel=1e-9, abs=1e-9)
                at_peak = values[(df["t"] == peaks.loc[joint, f"t_{kind}"]).to_numpy()]
                assert at_peak == pytest.approx([values.max()], rel=1e-9, abs=1e-9)
    assert set(QUANTITIES) <= set(peaks.columns)


def test_revolute_axes_carry_no_axial_moment_at_free_hinges(two_t1r):
    """A free revolute hinge transmits no moment about its axis: the axial moment of every unactuated
    tree joint is zero, and the actuated ones carry the efforts."""
    mech, r = two_t1r
    h = motion.peaks(r)
    by_joint = {p.joint: p for p in h}
    scale = np.abs(r.efforts).max()
    for joint in mech.model.names[1:]:
        if joint not in r.actuated:
            assert by_joint[joint].values["axial_moment"] < 1e-9 * scale
    for k, joint in enumerate(r.actuated):
        assert by_joint[joint].values["axial_moment"] == pytest.approx(np.abs(r.efforts[:, k]).max(), rel=1e-9)


def test_speed_benchmark_runs():
    """The benchmark's figures exist and are consistent (its timings are printed by tools/motion_speed.py,
    never asserted)."""
    from mechkit.bench.motion_speed import lines, motion_law_speed

    s = motion_law_speed(samples=6, repeats=1)
    assert s.samples == 6 and min(s.study_s, s.kinematics_s, s.dynamics_s, s.raw_constraint_dynamics_s) > 0
    assert lines(s)[-1].startswith("goal: the whole study under 50 ms")


def test_peaks_flag_indeterminate_joints(two_t1r):
    """The 2T1R is planar, modelled in space: its out-of-plane reaction parts are indeterminate."""
    _, r = two_t1r
    flags = {p.joint: p.determinate for p in motion.peaks(r)}
    assert set(flags.values()) <= {True, False} and False in flags.values()
    for j, joint in enumerate(r.joints):
        assert flags[joint] == bool(r.determinate[:, j].all())


def test_ten_bar_efforts_equal_the_deployment_dynamics(load_cached):
    """Along the ten-bar's deployment (constrained forward dynamics, its transient included), the study's
    efforts are the motor torques that realised the motion, and at the spring hinge R5 the spring and
    damper torque: forward and inverse dynamics agree."""
    from mechkit.mechanisms.ten_bar import dynamics as td

    mech = load_cached("ten_bar")
    system = td.PinocchioDeployment(mech)
    trajectory = td.deploy(system, mech.home_q, 0.02, t_end=0.3)
    names = motion.default_inputs(mech)
    idx = [mech.v_index(j) for j in names]
    states = [system.rhs(t, q, v) for t, q, v in zip(trajectory.t, trajectory.q, trajectory.v)]
    acc = np.array([s[0] for s in states])
    law = motion.from_arrays(mech, trajectory.t, trajectory.q[:, idx], trajectory.v[:, idx], acc[:, idx], names=names,
                             guesses=trajectory.q)
    r = motion.study(mech, law)
    assert np.allclose(r.v, trajectory.v, atol=1e-12) and np.allclose(r.a, acc, atol=1e-10)
    # the R5 input's driven force is what the spring does not supply: nothing, the motion is the spring's own
    expected = np.column_stack([np.array([s[1] for s in states]), np.zeros(len(states))])
    assert np.allclose(r.efforts, expected, rtol=1e-11, atol=1e-11 * np.abs(expected).max())
