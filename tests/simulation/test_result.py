"""`mechkit.simulation.result`: a simulation's balance terms by role (a torque supplies, friction dissipates),
against quadratures of the recorded motion; the table written as CSV and Parquet and read back whole."""

from __future__ import annotations

import json

import numpy as np
import pytest
import scipy.integrate

from mechkit import forces, simulation


@pytest.fixture(scope="module")
def driven_and_rubbing(four_bar):
    """0.3 s with 0.5 N m on the crank and 0.02 N m of constant friction on the rocker."""
    rub = forces.CoulombFriction(four_bar.model, {"rocker": 0.02})
    return four_bar.simulate(0.3, torques={"crank": 0.5}, forces=[rub])


def test_supplied_and_dissipated_follow_the_roles(four_bar, driven_and_rubbing):
    """The source's work is the supplied energy, the friction's the dissipated one (minus its work, equal to
    the friction power's quadrature), and the balance of all terms holds."""
    run = driven_and_rubbing
    assert run.roles == ("dissipative", "source") and run.element_names == ("joint friction", "crank")
    assert np.array_equal(run.supplied, run.drive_work + run.works[:, 1])
    assert np.array_equal(run.dissipated, -run.works[:, 0] + run.impact_loss)
    assert run.dissipated[-1] == pytest.approx(-scipy.integrate.simpson(run.friction_power, x=run.t), rel=1e-4)
    assert run.dissipated[-1] > 0 and run.supplied[-1] != 0
    assert run.energy_error <= 1e-6 * run.energy_scale
    assert run.column("rocker") == list(four_bar.model.names[1:]).index("rocker")


def test_the_csv_table_reads_back_at_full_precision(tmp_path, driven_and_rubbing):
    pd = pytest.importorskip("pandas")
    run = driven_and_rubbing
    path = simulation.write_csv(run, tmp_path / "run.csv")
    lines = path.read_text().splitlines()
    meta = {line[2:].split(": ", 1)[0]: line[2:].split(": ", 1)[1] for line in lines if line.startswith("# ")}
    assert json.loads(meta["elements"]) == {"joint friction": "dissipative", "crank": "source"}
    table = pd.read_csv(path, comment="#")
    columns = run.columns()
    assert list(table.columns) == list(columns)
    for name in ("t", "energy/balance", "work/crank", "power/friction", "closure_residual"):
        assert np.array_equal(table[name].to_numpy(), columns[name]), name


def test_the_parquet_table_keeps_the_metadata(tmp_path, driven_and_rubbing):
    pd = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    run = driven_and_rubbing
    df = pd.read_parquet(simulation.write_parquet(run, tmp_path / "run.parquet"))
    assert np.array_equal(df["energy/balance"].to_numpy(), run.balance)
    assert json.loads(df.attrs["integrator"])["steps"] == run.integrator["steps"]


def test_the_summary_states_the_balance(driven_and_rubbing):
    run = driven_and_rubbing
    lines = run.summary()
    assert lines[1] == f"closure residual: max {run.residual.max():.3g} m"
    assert f"drift {run.energy_error:.3g} J of {run.energy_scale:.6g} J exchanged" in lines[3]
