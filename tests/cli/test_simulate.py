"""`mechkit simulate`: the summary printed (energy balance, closure residual), the table written, errors in
one line, the help's examples."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechkit.cli import main


def test_simulate_four_bar_writes_parquet(tmp_path, capsys):
    pd = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    out = tmp_path / "free.parquet"
    assert (
        main(["simulate", "four_bar", "--duration", "0.2", "-o", str(out), "--plot", str(tmp_path / "free.png")]) == 0
    )
    text = capsys.readouterr().out
    assert "energy balance: drift" in text and "closure residual: max" in text
    df = pd.read_parquet(out)
    for column in (
        "t",
        "q/crank",
        "reaction/C/fx",
        "closure_residual",
        "energy/kinetic",
        "energy/balance",
        "power/friction",
    ):
        assert column in df.columns, column
    assert df["closure_residual"].max() <= 1e-10
    assert (tmp_path / "free.png").stat().st_size > 10_000


def test_simulate_with_friction_torques_csv_and_latch(tmp_path, capsys):
    law = tmp_path / "torque.csv"
    law.write_text("t,crank\n0,0.05\n0.3,0.05\n0.6,0.05\n1,0.05\n")
    assert (
        main(
            [
                "simulate",
                "four_bar",
                "--duration",
                "0.1",
                "--torques",
                str(law),
                "--friction",
                "0.1,0.005",
                "--latch",
                "crank=0.5",
                "-o",
                str(tmp_path / "t.csv"),
            ]
        )
        == 0
    )
    text = capsys.readouterr().out
    assert "dissipated" in text and (tmp_path / "t.csv").exists()


def test_errors_are_one_line(capsys):
    assert main(["simulate", "four_bar", "--duration", "-1"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechkit: error:") and err.count("\n") == 1


def test_help_ends_with_two_examples(capsys):
    with pytest.raises(SystemExit):
        main(["simulate", "--help"])
    lines = capsys.readouterr().out.rstrip().splitlines()
    assert lines[-3] == "examples:" and all(line.startswith("  mechkit simulate") for line in lines[-2:])


@pytest.mark.parametrize(
    "option, needle",
    [
        (["--latch", "crank"], "argument '--latch': expected JOINT=VALUE"),
        (["--latch", "crank=abc"], "'abc' is not a number"),
        (["--latch", "crank=0.5", "--latch", "crank=0.7"], "'crank' is given twice"),
        (["--spring", "crank=1"], "expected JOINT=STIFFNESS,REFERENCE[,DAMPING]: 1 number(s) given"),
        (["--friction", "0.1,nan"], "'nan' is not finite"),
        (["--gravity", "0,0"], "expected GX,GY,GZ"),
        (["--plot", "run.xyz"], "argument '--plot': expected a .png or .svg or .pdf file"),
        (["--animate", "run.png"], "argument '--animate': expected a .html file"),
        (["-o", "run.json"], "argument '-o': expected a .parquet or .csv file"),
        (["--duration", "nan"], "argument '--duration': must be a finite time > 0 s"),
        (["--restitution", "nan"], "argument '--restitution': must be in [0, 1]"),  # was named 'limit of crank'
        (["--restitution", "1.5"], "argument '--restitution': must be in [0, 1]"),
    ],
)
def test_malformed_options_are_refused_before_the_mechanism_loads(monkeypatch, capsys, option, needle):
    """A malformed --latch was a ValueError traceback and a plot format was checked after the whole run: both
    are refused in one line before any work (the mechanism is never loaded)."""
    from mechkit.cli import simulate

    def never(_args):
        raise AssertionError("the mechanism was loaded")

    monkeypatch.setattr(simulate, "load_mechanism", never)
    args = ["simulate", "four_bar", "--duration", "0.1", *option]
    if option[0] == "--duration":
        args = ["simulate", "four_bar", *option]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechkit: error:") and err.count("\n") == 1 and needle in err, err


def test_a_nan_in_a_torques_csv_is_named_with_its_row_and_column(tmp_path, capsys):
    law = tmp_path / "torques.csv"
    law.write_text("t,crank\n0,0\n0.02,0.01\n0.04,nan\n0.06,0.01\n")
    assert main(["simulate", "four_bar", "--duration", "0.05", "--torques", str(law)]) == 2
    assert f"{law}: line 4: column 'crank': 'nan' is not a finite number" in capsys.readouterr().err


def test_an_effort_never_driven_is_not_printed_as_nan():
    from mechkit.cli.simulate import effort_line

    nan = float("nan")
    assert (
        effort_line("latch", [nan, nan])
        == "effort latch: not computed (the joint was never driven or held in this run)"
    )
    assert effort_line("latch", [nan, 1.0, 3.0]) == "effort latch: 1 .. 3 (N m or N, driven at 2 of 3 samples)"
    assert effort_line("crank", [0.5, -2.0]) == "effort crank: -2 .. 0.5 (N m or N)"


def test_a_method_pinocchio_cannot_run_names_the_option_that_can(tmp_path, capsys):
    """A five-bar whose second crank mimics the first (a coupling row, which no Pinocchio constraint model
    expresses): by default kkt runs; asked for, proximal is refused with the option to type instead."""
    import re

    from tests_support import ROOT

    text = (ROOT / "urdf" / "five_bar.urdf").read_text()
    mimic = '<mimic joint="prox1" multiplier="1" offset="-0.9"/>'
    path = tmp_path / "five_mimic.urdf"
    path.write_text(re.sub(r'(<joint name="prox2" type="revolute">)', r"\1" + mimic, text))
    assert main(["simulate", str(path), "--duration", "0.02"]) == 0
    capsys.readouterr()
    assert main(["simulate", str(path), "--duration", "0.02", "--dynamics", "proximal"]) == 2
    assert "(on the command line: --dynamics kkt)" in capsys.readouterr().err


@pytest.mark.parametrize(
    "option, value, named",
    [
        (["--latch"], "nope=0.5", "argument '--latch': 'nope' is not a joint"),  # was 'joint'
        (["--spring"], "nope=1,0", "argument '--spring': 'nope' is not a joint"),  # was 'spring'
        (["--rtol"], "nan", "--rtol: must be > 0"),  # was 'rtol/atol/max_step'
    ],
)
def test_values_the_mechanism_or_the_integrator_refuses_are_named_as_typed(option, value, named, capsys):
    assert main(["simulate", "four_bar", "--duration", "0.01", *option, value]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"mechkit: error: {named}") and err.count("\n") == 1, err


def test_a_table_suffix_in_capitals_is_the_format_it_names(tmp_path, capsys):
    """`-o run.PARQUET` passed the (case-blind) suffix check and was written as CSV."""
    pd = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    out = tmp_path / "run.PARQUET"
    assert main(["simulate", "four_bar", "--duration", "0.01", "-o", str(out)]) == 0
    assert out.read_bytes()[:4] == b"PAR1" and "q/crank" in pd.read_parquet(out).columns


@pytest.mark.parametrize(
    "module, args", [("pandas", ["-o", "s.csv"]), ("pyarrow", ["-o", "s.parquet"]), ("matplotlib", ["--plot", "s.png"])]
)
def test_a_missing_library_is_refused_before_the_run(module, args, tmp_path, capsys, monkeypatch):
    """`-o run.parquet` without pyarrow was refused after the whole simulation; now before it loads."""
    from mechkit.cli import simulate

    monkeypatch.setitem(__import__("sys").modules, module, None)  # import fails as if not installed
    monkeypatch.setattr(simulate, "load_mechanism", lambda _args: pytest.fail("the mechanism was loaded"))
    monkeypatch.chdir(tmp_path)
    assert main(["simulate", "four_bar", "--duration", "5", *args]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "pip install" in err
    assert list(tmp_path.iterdir()) == []


# --- the forces helper's options: --torque, --no-limits, --friction-rate, loop-cut joints, two-sample laws


def _table(path):
    """A written CSV table: column name -> (samples,) values."""
    import numpy as np

    lines = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    header = lines[0].split(",")
    data = np.array([[float(x or "nan") for x in line.split(",")] for line in lines[1:]])  # empty: not computed
    return {h: data[:, k] for k, h in enumerate(header)}


def test_constant_torques_and_a_cut_joint_spring(tmp_path, capsys):
    """0.2 N m on the crank and 0.01 N m on the loop-cut pin C, a spring-damper on C: each torque's work in the
    table is the quadrature of torque x its joint's rate (C's: rocker - crank - coupler, planar, axes -y) to
    1e-5, and the balance stays constant to 1e-8 of the work supplied."""
    import scipy.integrate

    out = tmp_path / "run.csv"
    args = ["--torque", "crank=0.2", "--torque", "C=0.01", "--spring", "C=0.1,0,0.005", "--friction-rate", "0.05"]
    assert main(["simulate", "four_bar", "--duration", "0.2", *args, "-o", str(out)]) == 0
    capsys.readouterr()
    c = _table(out)
    rate_c = c["v/rocker"] - c["v/crank"] - c["v/coupler"]
    for column, rate, torque in (("work/torque on crank", c["v/crank"], 0.2), ("work/torque on C", rate_c, 0.01)):
        assert abs(c[column][-1]) > 1e-4
        assert c[column][-1] == pytest.approx(scipy.integrate.simpson(torque * rate, x=c["t"]), rel=1e-5)
    assert c["energy/balance"].max() - c["energy/balance"].min() <= 1e-8 * c["work/torque on crank"][-1]


def test_a_two_sample_torque_law_is_the_constant_it_draws(tmp_path, capsys):
    """A torque law of two samples (0.3 N m at 0 and 1 s) is the straight line between them: the run equals the
    one with --torque crank=0.3 (to 1e-12 rad)."""
    law = tmp_path / "torque.csv"
    law.write_text("t,crank\n0,0.3\n1,0.3\n")
    finals = []
    for extra in (["--torques", str(law)], ["--torque", "crank=0.3"]):
        out = tmp_path / "run.csv"
        assert main(["simulate", "four_bar", "--duration", "0.1", *extra, "-o", str(out)]) == 0
        finals.append(_table(out)["q/crank"][-1])
    capsys.readouterr()
    assert finals[0] > 0.6 + 1e-3 and finals[0] == pytest.approx(finals[1], abs=1e-12)


@pytest.mark.parametrize(
    "option, needle",
    [
        (["--torque", "crank"], "argument '--torque': expected JOINT=VALUE (N m or N)"),
        (["--friction-rate", "0"], "argument '--friction-rate': must be a finite rate > 0"),
        (["--friction-rate", "nan"], "argument '--friction-rate': must be a finite rate > 0"),
        (["--no-limits", "--restitution", "0.5"], "argument '--restitution': applies at the joint limits"),
    ],
)
def test_the_forces_options_are_checked_before_the_mechanism_loads(monkeypatch, capsys, option, needle):
    from mechkit.cli import simulate

    def never(_args):
        raise AssertionError("the mechanism was loaded")

    monkeypatch.setattr(simulate, "load_mechanism", never)
    assert main(["simulate", "four_bar", "--duration", "0.1", *option]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechkit: error:") and err.count("\n") == 1 and needle in err, err


def test_a_torque_on_no_joint_is_named_as_typed(capsys):
    assert main(["simulate", "four_bar", "--duration", "0.01", "--torque", "nope=1"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechkit: error: argument '--torque': 'nope' is not a joint") and err.count("\n") == 1, err


# --- end of the forces helper's tests


def test_no_limits_lets_a_joint_pass_the_files_stop(tmp_path, capsys):
    """The four-bar with its crank's range cut to [-1, 0.7] rad, driven by 0.5 N m: the file's stop holds the
    crank at 0.7 rad; with --no-limits it turns past."""
    from tests_support import ROOT

    full = 'lower="-1000000000.0" upper="1000000000.0"'
    path = tmp_path / "stopped.urdf"
    path.write_text((ROOT / "urdf" / "four_bar.urdf").read_text().replace(full, 'lower="-1" upper="0.7"', 1))
    finals = []
    for extra in ([], ["--no-limits"]):
        out = tmp_path / "run.csv"
        assert main(["simulate", str(path), "--duration", "0.3", "--torque", "crank=0.5", *extra, "-o", str(out)]) == 0
        finals.append(_table(out)["q/crank"][-1])
    capsys.readouterr()
    assert finals[0] == pytest.approx(0.7, abs=1e-9) and finals[1] > 1.0


FOUR_BARS = str(Path(__file__).resolve().parents[1] / "fixtures" / "iftomm" / "n_four_bar.urdf")


def test_v0_sets_one_rate_and_the_loops_give_the_others(capsys):
    """--v0 crank0=-1 on the IFToMM N four-bar (N = 2): the whole parallelogram moves, and the two singular
    positions of the first 1.5 s are passed on the branch and printed (without --v0 it would stay at rest,
    balanced upright)."""
    assert main(["simulate", FOUR_BARS, "--duration", "1.5", "--v0", "crank0=-1"]) == 0
    text = capsys.readouterr().out
    assert text.count("passed a singular position on its branch (mobility 3") == 2, text


@pytest.mark.parametrize(
    "values, needle",
    [
        (["crankX=-1"], "argument '--v0': 'crankX' is not a joint"),
        (["crank0=-1", "crank1=2"], "argument '--v0': the closures do not allow these rates together"),
        (["crank0"], "argument '--v0': expected JOINT=RATE"),
    ],
)
def test_v0_values_the_loops_refuse_are_named(values, needle, capsys):
    args = ["simulate", FOUR_BARS, "--duration", "0.1"]
    for value in values:
        args += ["--v0", value]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechkit: error:") and err.count("\n") == 1 and needle in err, err


def test_torque_sets_a_tendon_actuators_force_as_mujoco_does_with_its_control(tmp_path, capsys):
    """`--torque winch=-1` on the tendon pendulum (its motor's keyframe force 2 x 1.5 N replaced): the end of a
    0.5 s run agrees with MuJoCo (RK4, dt 1e-4 s) started from the keyframe with control -0.5 (gear 2) to 1e-7
    rad, and differs from the keyframe's own run by more than 0.01 rad (the force changed the motion)."""
    pd = pytest.importorskip("pandas")
    mujoco = pytest.importorskip("mujoco")
    from tests_support import FIXTURES

    source = FIXTURES / "tendon_pendulum.xml"

    def mujoco_end(ctrl: float) -> np.ndarray:
        mm = mujoco.MjModel.from_xml_path(str(source))
        mm.opt.timestep = 1e-4
        data = mujoco.MjData(mm)
        mujoco.mj_resetDataKeyframe(mm, data, 0)
        data.ctrl[:] = ctrl
        while data.time < 0.5 - 5e-5:
            mujoco.mj_step(mm, data)
        return data.qpos.copy()

    out = tmp_path / "run.csv"
    argv = ["simulate", str(source), "--duration", "0.5", "--rtol", "1e-10", "-o", str(out), "--torque", "winch=-1"]
    assert main(argv) == 0
    table = pd.read_csv(out, comment="#")
    end = table[["q/shoulder", "q/elbow"]].to_numpy()[-1]
    assert table["t"].iloc[-1] == pytest.approx(0.5)
    assert np.max(np.abs(end - mujoco_end(-0.5))) < 1e-7
    assert np.max(np.abs(end - mujoco_end(1.5))) > 0.01


def test_torque_on_a_name_no_joint_or_element_has_is_refused(capsys):
    from tests_support import FIXTURES

    assert main(["simulate", str(FIXTURES / "tendon_pendulum.xml"), "--duration", "0.1", "--torque", "pulley=1"]) == 2
    err = capsys.readouterr().err
    assert "--torque" in err and "pulley" in err and "winch" in err
