"""`mechkit.bench.iftomm`: the IFToMM problems' references (the N-four-bar's branch ODE, Bricard's reduced
one-coordinate ODE, the flyball governor by Pinocchio's ABA) against mechkit's simulator and MuJoCo, and the
library's high-precision criterion (1e-3 m) on the generated N = 40 four-bar (slow)."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit.base.exceptions import InvalidArgument
from mechkit.bench import iftomm
from mechkit.bench.iftomm_page import FIXTURES, four_bar_start
from mechkit.simulation.crossing import forward


@pytest.fixture(scope="module")
def bricard():
    return mechkit.load(FIXTURES / "bricard.urdf")


def _generated(tmp_path, n: int):
    path = tmp_path / f"n{n}.urdf"
    path.write_text(iftomm.n_four_bar_urdf(n))
    return mechkit.load(path)


def test_the_generated_n2_four_bar_is_the_fixture(tmp_path):
    """N = 2 written by the generator: the fixture's joints, placements and inertias to 1e-15."""
    mine, fixture = _generated(tmp_path, 2).model, mechkit.load(FIXTURES / "n_four_bar.urdf").model
    assert sorted(mine.names) == sorted(fixture.names)
    for name in fixture.names[1:]:
        a, b = mine.getJointId(name), fixture.getJointId(name)
        assert np.allclose(mine.jointPlacements[a].homogeneous, fixture.jointPlacements[b].homogeneous, atol=1e-15)
        assert np.allclose(mine.inertias[a].matrix(), fixture.inertias[b].matrix(), atol=1e-15)


@pytest.mark.parametrize("n", [0, -1, 2.0, True])
def test_a_four_bar_without_windows_is_refused(n):
    with pytest.raises(InvalidArgument, match="n"):
        iftomm.n_four_bar_urdf(n)


@pytest.mark.parametrize("theta", [1.0, 2.5])
def test_the_branch_ode_is_the_constrained_dynamics_of_a_generated_four_bar(tmp_path, theta):
    """N = 5: on the parallelogram branch every crank's acceleration from the closure dynamics is the
    one-coordinate ODE's -K cos(theta) (K derived by hand in `four_bar_gain`) to 1e-9."""
    m = _generated(tmp_path, 5)
    q, v = np.zeros(m.model.nq), 0.7 * four_bar_start(m, 5)
    for k in range(6):
        q[m.q_index(f"crank{k}")] = theta
    for k in range(1, 6):
        q[m.q_index(f"coupler{k}")] = -theta
    cm = m.closure_model
    a = forward(cm, cm.create_data(), q, v, np.zeros(m.model.nv))
    for k in range(6):
        assert a[m.v_index(f"crank{k}")] == pytest.approx(-iftomm.four_bar_gain(5) * np.cos(theta), abs=1e-9)


def test_bricard_s_reduced_ode_and_mechkit_agree(bricard):
    """1.5 s from rest: mechkit's defaults and the reduced one-coordinate ODE (Pinocchio alone) put every
    joint's origin within 1e-6 m of each other (measured 1.8e-8 m over 10 s); the chart's poses closed to 1e-12."""
    run = bricard.simulate(1.5, limits=None, reactions=False)
    chart = iftomm.BricardChart(bricard.model)
    ref = chart.run(run.t)
    assert max(np.max(np.abs(chart.residual(q)[0])) for q in ref) < 1e-12
    error = iftomm.point_error(bricard.model, run.motion.q, ref)
    assert error < 1e-6 and float(np.max(np.ptp(ref[:, 0]))) > 1.0  # and it moved by more than a radian


def test_mujoco_on_the_exported_bricard_follows_the_reduced_ode(bricard):
    """MuJoCo (exported model, its stiff equalities, RK4) within 1e-5 m of the reduced ODE over 1 s."""
    pytest.importorskip("mujoco")
    t, q, _ = iftomm.mujoco_run(bricard, 1.0)
    ref = iftomm.BricardChart(bricard.model).run(t[::20])
    assert iftomm.point_error(bricard.model, q[::20], ref) < 1e-5


def test_the_flyball_governor_s_pinocchio_reference_and_mechkit_agree():
    """0.05 s of the transient: mechkit (RK45 at rtol 1e-8: cheap over so short a run) and the reference (ABA
    + the springs written apart, Radau 1e-10) give the same slider position s to 1e-9 m; the slider moved."""
    path = FIXTURES / "flyball_governor.urdf"
    m = mechkit.load(path)
    v0 = np.zeros(m.model.nv)
    v0[m.v_index("shaft")] = 2 * np.pi
    run = m.simulate(0.05, v0=v0, rtol=1e-8, limits=None, reactions=False)
    ref = iftomm.flyball_reference(pin.buildModelFromUrdf(str(path)), 0.05)
    s = run.motion.q[:, m.q_index("s")]
    assert np.max(np.abs(s - ref.sol(run.t)[2])) < 1e-9 and abs(s[-1] - s[0]) > 1e-3


@pytest.mark.slow
def test_n40_four_bar_passes_its_singular_positions_within_high_precision(tmp_path):
    """The library's N = 40 over 20 s: 20 singular positions passed on the branch, B0 within 1e-5 m of the
    branch ODE (measured 4.3e-6 m; the high-precision bound 1e-3), the cranks together to 1e-9 rad."""
    m = _generated(tmp_path, 40)
    run = m.simulate(20.0, v0=four_bar_start(m, 40), limits=None, reactions=False)
    assert run.integrator["singular_crossings"] == 20
    crank = run.motion.q[:, [m.q_index(f"crank{k}") for k in range(41)]]
    assert np.max(np.abs(crank - crank[:, :1])) < 1e-9
    theta = iftomm.four_bar_reference(40, run.t)
    assert np.max(np.hypot(np.cos(crank[:, 0]) - np.cos(theta), np.sin(crank[:, 0]) - np.sin(theta))) < 1e-5


@pytest.mark.slow
def test_the_flyball_governor_meets_high_precision_over_its_ten_seconds():
    """The library's 10 s with RK45 at rtol 1e-6 (stability-bound, ~1.5e4 steps): s within 1e-6 m of the
    reference (measured 3.7e-10 m; the high-precision bound 1e-3 m)."""
    from mechkit.bench.iftomm_page import run_flyball

    row = run_flyball(10.0, "RK45", 1e-6)
    assert row.error < 1e-6 and row.passed


@pytest.mark.slow
def test_the_flyball_governor_by_radau_meets_high_precision_in_fewer_steps_than_rk45():
    """The library's 10 s with Radau at rtol 1e-6 (the analytic Jacobian, `mechkit.simulation.jacobian`): s within
    1e-6 m of the reference (measured 1.4e-8 m) in under a tenth of RK45's ~1.5e4 steps (measured 696)."""
    from mechkit.bench.iftomm_page import run_flyball

    row = run_flyball(10.0, "Radau", 1e-6, mujoco=False)
    assert row.error < 1e-6 and row.passed and row.steps < 1500


@pytest.mark.slow
def test_bricard_over_the_benchmark_s_ten_seconds_against_the_reduced_ode():
    """The library's 10 s: every joint's origin within 1e-6 m of the reduced ODE (measured 1.8e-8 m, the
    reference's own floor), MuJoCo's run measured beside it."""
    from mechkit.bench.iftomm_page import run_bricard

    row = run_bricard(10.0)
    assert row.error < 1e-6 and row.passed
