"""Sweeps: design spaces, the motion study's physics, statuses of failing designs, the Parquet store,
the embedded Dask cluster and resuming."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit.base.exceptions import InvalidParameters
from mechkit.sweep import DesignSpace, Study, parse_axis, read, sweep
from mechkit.sweep.evaluate import Chunk, evaluate_chunk
from mechkit.sweep.metrics import motion_samples
from mechkit.sweep.specific import resolve


def test_axes_and_spaces():
    grid = DesignSpace((parse_axis("crank=0.05:0.15:3"), parse_axis("ground=0.25:0.35:2")))
    designs = grid.designs()
    assert designs.shape == (6, 2)
    assert np.allclose(designs[:, 0], [0.05, 0.05, 0.10, 0.10, 0.15, 0.15])
    n = 20
    lhs = DesignSpace((parse_axis("crank=0:1"), parse_axis("ground=2:4")), "lhs", n, seed=3).designs()
    for j, (lo, hi) in enumerate([(0, 1), (2, 4)]):  # one sample in each of the n strata of every axis
        strata = np.floor((lhs[:, j] - lo) / (hi - lo) * n).astype(int)
        assert sorted(strata) == list(range(n))
    rand = DesignSpace((parse_axis("crank=0:1"),), "random", 50, seed=1).designs()
    assert rand.min() >= 0 and rand.max() <= 1
    assert np.array_equal(rand, DesignSpace((parse_axis("crank=0:1"),), "random", 50, seed=1).designs())
    for bad in ("crank", "crank=1:0:3", "crank=a:1:2", "crank=0:1:0"):
        with pytest.raises(InvalidParameters):
            parse_axis(bad)
    with pytest.raises(InvalidParameters):
        DesignSpace((parse_axis("crank=0:1"),)).designs()  # a grid axis needs a count


def test_motion_study_power_balance():
    """tau * omega = d(kinetic + potential energy)/dt along a crank turn at constant speed."""
    mech = mechkit.load("four_bar")
    study = Study(law="turn", samples=400)
    s = motion_samples(mech, study)
    omega = 2 * math.pi / study.period
    energy = []
    for q in s.q:
        v = mech.velocities(q, [omega])
        energy.append(pin.computeKineticEnergy(mech.model, mech.data, q, v)
                      + pin.computePotentialEnergy(mech.model, mech.data, q))
    dE = (np.roll(energy, -1) - np.roll(energy, 1)) / (2 * study.period / study.samples)  # periodic motion
    power = s.efforts[:, 0] * omega
    assert np.max(np.abs(power - dE)) < 2e-3 * np.max(np.abs(power))
    assert np.max(s.residual) < 1e-9
    assert np.all(s.inv_cond > 0)


def _rows(values, study=None, metrics=None):
    study = study or Study(law="turn", samples=60)
    mech = mechkit.load("four_bar")
    chosen = resolve("four_bar", metrics)
    columns = tuple(c for m in chosen for c in m.columns(mech))
    names = ("crank", "ground", "coupler", "rocker")[:len(values[0])]
    chunk = Chunk("four_bar", {}, names, tuple(range(len(values))), np.array(values, float),
                  study, tuple(m.name for m in chosen), columns)
    return evaluate_chunk(chunk), columns


def test_failing_designs_are_rows_with_their_status():
    rows, columns = _rows([[0.10, 0.30, 0.28, 0.22],   # the default crank-rocker
                           [0.25, 0.30, 0.30, 0.05],   # at the home crank angle C is 0.17 m from D < 0.30 - 0.05
                           [0.20, 0.40, 0.28, 0.22],   # assembles, but the crank cannot turn fully: a dead point
                           [-0.1, 0.30, 0.28, 0.22],   # invalid parameter
                           [0.10, 1.00, 0.28, 0.22]])  # ground longer than the three others (params refuse it)
    assert [r["status"] for r in rows] == ["ok", "does_not_assemble", "singular", "error", "error"]
    ok = rows[0]
    assert ok["closure_residual"] < 1e-9 and 0 < ok["singularity_distance"] <= 1 and ok["branch"] in (-1.0, 1.0)
    assert ok["message"] == ""
    for row in rows[1:]:
        assert all(math.isnan(row[c]) for c in columns) and row["message"]
    assert "crank" in rows[3]["message"] and "longest link" in rows[4]["message"]
    assert "ClosureNotConverged" in rows[1]["message"] and "sample" in rows[2]["message"]


def test_ground_pins_carry_the_weight():
    """Quasi-statically slow, the two ground pins (crank at A, rocker at D) carry the linkage's weight:
    |f_A| + |f_D| >= m g at every sample, with equality of the vertical sum (checked through the
    peak columns' lower bound)."""
    mech = mechkit.load("four_bar")
    s = motion_samples(mech, Study(law="turn", samples=40, period=1e4))
    weight = 9.81 * sum(i.mass for i in mech.model.inertias)
    pins = s.forces[:, [s.joints.index("crank"), s.joints.index("rocker")]].sum(axis=1)
    assert np.all(pins >= weight * (1 - 1e-9))
    rows, _ = _rows([[0.10, 0.30]], Study(law="turn", samples=40, period=1e4), ("peak_force", "peak_effort"))
    assert rows[0]["peak_force.crank"] + rows[0]["peak_force.rocker"] >= weight * (1 - 1e-9)
    assert rows[0]["peak_force.crank"] == pytest.approx(s.forces[:, s.joints.index("crank")].max(), rel=1e-9)


def test_sweep_on_embedded_cluster_and_resume(tmp_path):
    space = DesignSpace((parse_axis("crank=0.06:0.2:4"), parse_axis("ground=0.28:0.40:3")))
    study = Study(law="turn", samples=30)
    out = tmp_path / "r"
    first = sweep("four_bar", space, out, study, workers=1, chunk_size=5)
    frame = read(out)
    assert list(frame["index"]) == list(range(12)) and first.evaluated == 12
    assert first.statuses.get("ok", 0) > 0 and first.statuses.get("singular", 0) > 0
    with pytest.raises(InvalidParameters):  # not overwritten without --resume
        sweep("four_bar", space, out, study, workers=1, chunk_size=5)
    (out / "parts" / "part-000001.parquet").unlink()  # as if killed before that chunk finished
    again = sweep("four_bar", space, out, study, workers=1, chunk_size=5, resume=True)
    assert again.evaluated == 5
    resumed = read(out)
    assert list(resumed["index"]) == list(range(12))
    assert resumed.drop(columns="seconds").equals(frame.drop(columns="seconds"))
    with pytest.raises(InvalidParameters):  # another sweep in the same folder
        sweep("four_bar", space, out, Study(law="turn", samples=31), workers=1, chunk_size=5, resume=True)


def test_optimise_improves_on_the_best_sweep_design(tmp_path):
    from mechkit.sweep.optimise import optimise

    space = DesignSpace((parse_axis("crank=0.06:0.12:3"), parse_axis("rocker=0.18:0.26:3")))
    study = Study(law="turn", samples=30, period=0.5)
    out = tmp_path / "r"
    sweep("four_bar", space, out, study, ("peak_effort",), workers=1)
    column = "peak_effort.crank"
    frame = read(out)
    refined = optimise(out, column, starts=1, max_evaluations=15, workers=1)[0]
    assert refined.start_value == pytest.approx(frame[frame["status"] == "ok"][column].min())
    assert refined.value <= refined.start_value and 1 < refined.evaluations <= 16
    for axis in space.axes:
        assert axis.lo <= refined.best[axis.name] <= axis.hi
    again = evaluate_chunk(Chunk("four_bar", {}, space.names, (0,), np.array([list(refined.best.values())]),
                                 study, ("peak_effort",), ("peak_effort.crank",)))[0]
    assert again["status"] == "ok" and again[column] == pytest.approx(refined.value, rel=1e-9)


def test_pareto_front_and_plots(tmp_path):
    from mechkit.sweep.plots import heat_map, pareto_mask, pareto_plot

    rng = np.random.default_rng(5)
    a, b = rng.random(200), rng.random(200)
    a[3] = np.nan
    front = pareto_mask(a, b)
    assert not front[3] and front.any()
    for i in range(len(a)):  # off the front: beaten by a point of the front; on it: beaten by none
        if np.isnan(a[i]):
            continue
        beaten = front & (a <= a[i]) & (b <= b[i]) & ((a < a[i]) | (b < b[i]))
        assert beaten.any() != front[i]
    import pandas as pd

    frame = pd.DataFrame({"x": np.repeat([1.0, 2.0], 2), "y": np.tile([1.0, 2.0], 2), "m": [1.0, 2.0, 3.0, np.nan],
                          "n": [4.0, 3.0, 1.0, np.nan], "status": ["ok", "ok", "ok", "singular"]})
    assert heat_map(frame, "x", "y", "m", tmp_path / "h.png").stat().st_size > 1000
    assert pareto_plot(frame, "m", "n", tmp_path / "p.png").stat().st_size > 1000
    with pytest.raises(InvalidParameters):
        heat_map(frame, "x", "y", "nope", tmp_path / "h.png")
