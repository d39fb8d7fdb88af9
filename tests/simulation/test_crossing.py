"""`mechkit.simulation.crossing`: the IFToMM benchmarks "N four-bar mechanism" (N = 2: a singular position
at every horizontal pass, mobility 1 -> 3) and "Bricard's mechanism" (one redundant constraint) simulated
on their branch, against an independent reduced model (the parallelogram's one-crank ODE by scipy at
1e-12), the energy balance, the closure and the rank; a velocity across the other branch's tangent
refused by name. Fixtures: tests/fixtures/iftomm/ (README there: definitions, sources, CPU times)."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import mechkit
from mechkit import core, simulation
from mechkit.simulation.crossing import BranchChanged, BranchWatch, forward

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures" / "iftomm"
CRANKS = ("crank0", "crank1", "crank2")
#: The parallelogram's one-crank ODE theta'' = -K cos(theta): 3 cranks of I = m L^2 / 3 and 2 couplers
#: translating at L theta' give the mass m L^2 (1 + 2) = 3 kg m^2; their weights the potential
#: g m L (3 / 2 + 2) sin(theta) = 3.5 g sin(theta).
K = 3.5 * 9.81 / 3.0


@pytest.fixture(scope="module")
def four_bar():
    return mechkit.load(FIXTURES / "n_four_bar.urdf")


@pytest.fixture(scope="module")
def bricard():
    return mechkit.load(FIXTURES / "bricard.urdf")


def parallelogram(m, theta: float, rate: float) -> tuple[np.ndarray, np.ndarray]:
    """The parallelogram state at crank angle theta (rad from +x) and crank rate (rad/s)."""
    q, v = np.zeros(m.model.nq), np.zeros(m.model.nv)
    for j in CRANKS:
        q[m.q_index(j)], v[m.v_index(j)] = theta, rate
    for j in ("coupler1", "coupler2"):
        q[m.q_index(j)], v[m.v_index(j)] = -theta, -rate
    return q, v


def reference(t: np.ndarray) -> np.ndarray:
    """The reduced model's crank angle at times t (B0 starts up at +1 m/s along x: theta' = -1 rad/s)."""
    sol = solve_ivp(
        lambda _, y: [y[1], -K * np.cos(y[0])],
        (0.0, t[-1]),
        [np.pi / 2, -1.0],
        rtol=1e-12,
        atol=1e-12,
        dense_output=True,
    )
    return sol.sol(t)[0]


def test_accelerations_on_the_branch_match_the_reduced_model_up_to_the_singular_position(four_bar):
    """`forward` on the parallelogram at 1 rad, 1e-3 rad and 1e-7 rad from the flat position (singular-value
    ratio down to ~1e-7): every crank's acceleration is the reduced model's -K cos(theta) to 1e-9 (1e-6 at
    1e-7 rad: rounding amplified by the inverse of the smallest singular value, measured 2e-8)."""
    m = four_bar
    cm = m.closure_model
    for theta, tol in ((1.0, 1e-9), (1e-3, 1e-9), (1e-7, 1e-6)):
        q, v = parallelogram(m, theta, 2.0)
        a = forward(cm, cm.create_data(), q, v, np.zeros(m.model.nv))
        for j in CRANKS:
            assert a[m.v_index(j)] == pytest.approx(-K * np.cos(theta), abs=tol)


def test_a_velocity_along_another_branch_is_refused_by_name(four_bar):
    """1e-3 rad from the flat position on the parallelogram, a velocity that turns crank1 against crank0
    (the crossed branch's direction) is removed by the projection: `BranchChanged` names the time and a
    joint; the parallelogram's own velocity passes."""
    m = four_bar
    watch = BranchWatch(m, m.home_q)
    p = simulation.Projection(m)
    q, v = parallelogram(m, 1e-3, 2.0)
    watch.check(0.5, q - 1e-3, q, v, q, p.velocities(q, v, simulation.Drives(), 0.5))
    crossed = v.copy()
    crossed[m.v_index("crank1")] *= -1
    with pytest.raises(BranchChanged, match=r"t = 0.5 s, joint '\w+'") as err:
        watch.check(0.5, q - 1e-3, q, crossed, q, p.velocities(q, crossed, simulation.Drives(), 0.5))
    assert err.value.change > 1e-2


def test_the_kinetic_energy_test_is_a_branch_test_only_near_a_singular_position(four_bar):
    """The same velocity across the tangent: refused 1e-3 rad from the flat position even when the step was
    not searching (the end's ratio is below NEAR there), let through at the crank's quarter turn, where the
    tangent is unique (there the projection's change is the step's own error, not a branch)."""
    m = four_bar
    watch = BranchWatch(m, m.home_q)
    p = simulation.Projection(m)
    for angle, refused in ((1e-3, True), (np.pi / 4, False)):
        q, v = parallelogram(m, angle, 2.0)
        crossed = v.copy()
        crossed[m.v_index("crank1")] *= -1
        projected = p.velocities(q, crossed, simulation.Drives(), 0.5)
        if refused:
            with pytest.raises(BranchChanged):
                watch.check(0.5, q - 1e-3, q, crossed, q, projected, searching=False)
        else:
            watch.check(0.5, q - 1e-3, q, crossed, q, projected, searching=False)


def test_a_coarse_fixed_step_away_from_singular_positions_is_not_a_branch_change(load_cached):
    """The five-bar falling free under semi-implicit Euler at 2 ms: its velocity leaves the tangent by
    1.7e-4 of the kinetic energy a step at 40 rad/s, far from any singular position (it was refused as a
    branch change at t = 0.328 s); it runs its second, closed to rounding, and the step's own error shows
    where it belongs, in the energy balance (first order: about a fifth of the energy exchanged)."""
    m = load_cached("five_bar")
    r = m.simulate(1.0, method="SymplecticEuler", dt=2e-3, reactions=False)
    assert r.motion.t[-1] == pytest.approx(1.0) and r.residual.max() < 1e-12
    assert r.energy_error > 1e-2 * r.energy_scale


def test_n_four_bar_passes_every_singular_position_on_its_branch(four_bar):
    """The benchmark's 10 s: 10 horizontal passes (the reference's sign changes of sin(theta)), each
    reported as a crossing at mobility 3; the cranks stay equal (the parallelogram's invariant) to 1e-9 rad;
    the energy balance drifts < 1e-7 of the energy exchanged; B0 (crank0's tip) within 1e-5 m of the reduced
    model at every accepted step, the end included (the IFToMM library's high-precision bound: 1e-3)."""
    m = four_bar
    _, v0 = parallelogram(m, np.pi / 2, -1.0)
    start = time.process_time()
    r = m.simulate(10.0, v0=v0, limits=None, reactions=False)
    cpu = time.process_time() - start
    q = r.motion.q
    cranks = q[:, [m.q_index(j) for j in CRANKS]]
    assert np.max(np.abs(cranks - cranks[:, :1])) < 1e-9
    theta = reference(r.t)
    passes = int(np.sum(np.diff(np.sign(np.sin(theta))) != 0))
    crossings = [e for e in r.events if e[1].startswith("singular:")]
    assert passes == 10 and len(crossings) == passes and r.integrator["singular_crossings"] == passes
    assert all("mobility 3" in e[2] for e in crossings)
    assert r.energy_error <= 1e-7 * r.energy_scale
    assert float(np.max(r.residual)) <= 1e-10
    b0 = np.column_stack([np.cos(cranks[:, 0]), np.sin(cranks[:, 0])])
    error = np.linalg.norm(b0 - np.column_stack([np.cos(theta), np.sin(theta)]), axis=1)
    print(
        f"\nN four-bar 10 s: {len(r.t) - 1} steps, CPU {cpu:.2f} s, B0 error max {error.max():.2e} m, "
        f"end {error[-1]:.2e} m, energy drift {r.energy_error:.2e} J"
    )
    assert error.max() < 1e-5  # the IFToMM library's high-precision bound is 1e-3


def _bricard_run(m, duration: float):
    start = time.process_time()
    r = m.simulate(duration, limits=None, reactions=False)
    return r, time.process_time() - start


def test_bricard_keeps_energy_closure_and_its_mobility(bricard):
    """Released at rest, 2 s: one redundant row found (5 rows of rank 4, mobility 1) at every sample, the
    loop closed to 1e-10 m, the energy balance within 1e-7 of the energy exchanged, and the mechanism
    moving (kinetic energy reaches > 1 J)."""
    m = bricard
    r, cpu = _bricard_run(m, 2.0)
    cm = m.closure_model
    cd = cm.create_data()
    for q in r.motion.q[:: max(1, len(r.t) // 20)]:
        s = np.linalg.svd(core.closure_jacobian(cm, cd, q), compute_uv=False)
        assert m.model.nv - core.numerical_rank(s) == 1 and s.size - core.numerical_rank(s) == 1
    assert r.integrator["redundant_rows"] == 1
    assert float(np.max(r.residual)) <= 1e-10
    assert r.energy_error <= 1e-7 * r.energy_scale and float(np.max(r.kinetic)) > 1.0
    print(f"\nBricard 2 s: {len(r.t) - 1} steps, CPU {cpu:.2f} s, energy drift {r.energy_error:.2e} J")


@pytest.mark.slow
def test_bricard_over_the_benchmarks_ten_seconds(bricard):
    """The benchmark's 10 s: closure <= 1e-10 m, energy within 1e-7 of the energy exchanged."""
    r, cpu = _bricard_run(bricard, 10.0)
    assert float(np.max(r.residual)) <= 1e-10 and r.energy_error <= 1e-7 * r.energy_scale
    print(f"\nBricard 10 s: {len(r.t) - 1} steps, CPU {cpu:.2f} s, energy drift {r.energy_error:.2e} J")
